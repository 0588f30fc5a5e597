/* The outputs of one run, written all together or not at all.
 *
 * A tool records the files it reads (sh_outputs_input: the scene, and with
 * sh_outputs_scene_inputs every mesh, heightfield and light map it names,
 * and the files its meshes' loads read: an OBJ's material library, a
 * glTF's buffers and images)
 * and the files it will write (sh_outputs_add). An output that is one of
 * the inputs or another output of the same run is refused before any work:
 * paths are compared once resolved (realpath(3) of an existing file, of the
 * parent directory joined to the name of a new one) and existing files also
 * by device and inode, so "./s.json", "d/../s.json", a symbolic link and a
 * hard link are all the same file. An existing output that is not a
 * regular file (a directory, /dev/null, a FIFO) is refused too, since
 * publishing replaces it.
 *
 * Writing stages each file in an unnamed temporary file (O_TMPFILE) in its
 * destination's directory; sh_outputs_publish gives every staged file its
 * name (linkat, then rename over the destination) once all of them are
 * complete, with SIGINT and SIGTERM held back meanwhile. So a run that
 * fails, is interrupted or is killed, even by SIGKILL, leaves no output and
 * no temporary file. Where the file system has no O_TMPFILE (or /proc is
 * missing) a hidden named temporary ".NAME.<pid>.<n>.EXT" is used instead;
 * sh_outputs_free and sh_outputs_on_signal remove those, so only SIGKILL can
 * leave one behind there. A rename that fails after others succeeded
 * (a full disk cannot cause it: every byte is written before) is reported
 * and leaves the earlier outputs published.
 *
 * Errors: SH_ERR_ARG for a refused output (the message names both paths
 * and what each is), SH_ERR_IO for a file that cannot be written,
 * SH_ERR_NOMEM. Not thread-safe: one set belongs to one thread. */
#ifndef SH_OUTPUTS_H
#define SH_OUTPUTS_H

#include <stddef.h>

#include "sh_error.h"
#include "sh_image.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_outputs sh_outputs;

/* A new, empty set, or NULL out of memory. */
sh_outputs *sh_outputs_new(void);

/* Discards every file staged and not published, and frees the set. */
void sh_outputs_free(sh_outputs *set);

/* Records an input file; `what` names it in messages ("the scene"). A path
 * that does not resolve is recorded as given. */
sh_status sh_outputs_input(sh_outputs *set, const char *path, const char *what,
                           sh_error *err);

/* Records the scene's file and every file it loaded (meshes, heightfields,
 * light maps) as inputs. */
sh_status sh_outputs_scene_inputs(sh_outputs *set, const sh_scene *scene,
                                  sh_error *err);

/* Records an output; `what` names it in messages ("-o", "--stats"). Refused
 * with SH_ERR_ARG if it is an input or an output already recorded, or an
 * existing file that is not a regular file; SH_ERR_IO if its directory
 * cannot be resolved. */
sh_status sh_outputs_add(sh_outputs *set, const char *path, const char *what,
                         sh_error *err);

/* Stages `size` bytes as the output `path` (recorded with sh_outputs_add
 * first, or now as "an output"). */
sh_status sh_outputs_write_bytes(sh_outputs *set, const char *path,
                                 const void *data, size_t size, sh_error *err);

/* Stages an image as the output `path`, as sh_image_write_meta encodes it
 * (format by extension, exposure for 8-bit formats, attrs as metadata). */
sh_status sh_outputs_write_image(sh_outputs *set, const char *path,
                                 const sh_image *img, double exposure,
                                 const char *const *attrs, sh_error *err);

/* Gives every staged output its name. On failure nothing staged is left
 * (see above for a rename that fails midway). A set is published once. */
sh_status sh_outputs_publish(sh_outputs *set, sh_error *err);

/* Removes the named temporaries of every set not yet published. Only
 * async-signal-safe calls: for a SIGINT or SIGTERM handler, which then
 * ends the process (the sets are not usable afterwards). */
void sh_outputs_on_signal(void);

#ifdef __cplusplus
}
#endif
#endif
