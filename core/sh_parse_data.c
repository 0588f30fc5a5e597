/* The scene parser's meshes from memory: a mesh shape's "data" key names
 * one of the meshes the caller passed to sh_scene_parse_ex (shafts.h); the
 * mesh is checked and copied into the shape. */
#include "sh_parse_int.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reports an unknown mesh name at "data", with a suggestion or the list of
 * the names there are. */
static sh_status unknown_mesh(sh__parser *p, const char *name) {
  sh__pctx *c = &p->c;
  if (p->nmeshes == 0)
    return sh__fail_at(c, "data", SH_ERR_SCENE,
                       "unknown mesh '%s'; no meshes were passed in memory",
                       name);
  const char **names = calloc((unsigned)p->nmeshes + 1u, sizeof *names);
  if (!names) return sh__fail_at(c, "data", SH_ERR_NOMEM, "out of memory");
  for (int i = 0; i < p->nmeshes; i++) names[i] = p->meshes[i].name;
  sh_status st = sh__fail_unknown(c, "data", "mesh", name, names,
                                  "the meshes in memory are");
  free(names);
  return st;
}

/* Checks the arrays of mesh `d`: counts, finite positions, indices in
 * range. Errors are located at "data". */
static sh_status check_mesh(sh__parser *p, const sh_mesh_data *d) {
  sh__pctx *c = &p->c;
  if (d->nvertices < 0 || d->ntriangles < 0 ||
      (d->nvertices > 0 && !d->positions) ||
      (d->ntriangles > 0 && !d->indices))
    return sh__fail_at(c, "data", SH_ERR_SCENE,
                       "the mesh '%s' has %d vertices and %d triangles but "
                       "no arrays for them",
                       d->name, d->nvertices, d->ntriangles);
  if (d->ntriangles == 0)
    return sh__fail_at(c, "data", SH_ERR_SCENE,
                       "the mesh '%s' has no triangles", d->name);
  if (d->ntriangles > (int)(0x7fffffff / 3) ||
      d->nvertices > (int)(0x7fffffff / 3))
    return sh__fail_at(c, "data", SH_ERR_SCENE,
                       "the mesh '%s' is too large", d->name);
  for (long i = 0; i < 3L * d->nvertices; i++)
    if (!isfinite(d->positions[i]))
      return sh__fail_at(c, "data", SH_ERR_SCENE,
                         "the mesh '%s' has a non-finite position: "
                         "coordinate %ld of vertex %ld",
                         d->name, i % 3, i / 3);
  for (long i = 0; i < 3L * d->ntriangles; i++)
    if (d->indices[i] < 0 || d->indices[i] >= d->nvertices)
      return sh__fail_at(c, "data", SH_ERR_SCENE,
                         "the mesh '%s' has an index out of range: triangle "
                         "%ld refers to vertex %d, and there are %d vertices",
                         d->name, i / 3, d->indices[i], d->nvertices);
  return SH_OK;
}

sh_status sh__parse_mesh_data(sh__parser *p, json_t *o, sh_mesh *mesh,
                              char **name_out) {
  sh__pctx *c = &p->c;
  const char *name;
  const sh_mesh_data *d = NULL;
  sh_status st;
  if ((st = sh__string(c, o, "data", 1, &name))) return st;
  for (int i = 0; i < p->nmeshes && !d; i++)
    if (strcmp(p->meshes[i].name, name) == 0) d = &p->meshes[i];
  if (!d) return unknown_mesh(p, name);
  if ((st = check_mesh(p, d))) return st;
  size_t np = 3 * (size_t)d->nvertices, ni = 3 * (size_t)d->ntriangles;
  mesh->positions = malloc(np * sizeof *mesh->positions);
  mesh->indices = malloc(ni * sizeof *mesh->indices);
  *name_out = strdup(name);
  if (!mesh->positions || !mesh->indices || !*name_out)
    return sh__fail_at(c, "data", SH_ERR_NOMEM, "out of memory");
  memcpy(mesh->positions, d->positions, np * sizeof *mesh->positions);
  for (size_t i = 0; i < ni; i++) mesh->indices[i] = (unsigned)d->indices[i];
  mesh->nverts = d->nvertices;
  mesh->ntris = d->ntriangles;
  return SH_OK;
}
