/* Confinement of the files a scene names to the scene's directory tree.
 *
 * A scene, a mesh (an OBJ's material library, a glTF's buffers and images)
 * or an image may name other files; none outside the tree of the scene's
 * directory is ever opened because of such a name. A name is checked after
 * it is resolved: joined to its directory, normalised and with every
 * symbolic link followed (realpath(3)), so "..", "//", "./" and links that
 * point out are all caught, whatever spelling led there. Internal to the
 * core library. */
#ifndef SH_CONFINE_H
#define SH_CONFINE_H

#include "sh_error.h"

/* 1 if `path` resolves to `root` or a file below it (both resolved with
 * realpath; `root` NULL or "" means the current directory), 0 if it lies
 * outside, -1 if it cannot be resolved (it does not exist: errno is set). On
 * 1 or 0, *resolved (if not NULL) receives the resolved path (caller
 * frees); on -1 it is NULL. */
int sh__confined(const char *path, const char *root, char **resolved);

/* As sh__confined, but a `path` that does not exist is placed all the same:
 * its deepest existing ancestor resolved (links followed) and the rest of
 * its components joined with "." and ".." taken by name. So a missing
 * "../x.obj" is outside the tree before it is missing, and the scene is
 * told which. -1 only if the root cannot be resolved or memory runs out. */
int sh__confined_name(const char *path, const char *root, char **resolved);

#endif
