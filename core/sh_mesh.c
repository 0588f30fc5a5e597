/* Triangle meshes: files through assimp's C API, and heightfields. assimp
 * reads OBJ, PLY, glTF, STL, FBX and many more behind one call, applies the
 * node transforms and triangulates polygons, so the loader stays small. It
 * is loaded on the first mesh file (sh_assimp.h), not linked. */
#include "sh_mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <limits.h>
#include <locale.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sh_assimp.h"
#include "sh_confine.h"
#include "sh_file.h"
#include "sh_gltf_check.h"
#include "sh_obj_check.h"
#include "sh_off.h"
#include "sh_ply.h"

void sh_mesh_free(sh_mesh *mesh) {
  if (!mesh)
    return;
  free(mesh->positions);
  free(mesh->indices);
  memset(mesh, 0, sizeof *mesh);
}

/* Allocates the arrays of a mesh of nverts vertices and ntris triangles. */
static sh_status sh__mesh_alloc(sh_mesh *mesh, size_t nverts, size_t ntris,
                                const char *what, sh_error *err) {
  memset(mesh, 0, sizeof *mesh);
  if (nverts > (size_t)INT_MAX / 3 || ntris > (size_t)INT_MAX / 3)
    return sh_error_set(err, SH_ERR_MESH,
                        "%s has too many vertices or triangles (%zu, %zu)",
                        what, nverts, ntris);
  mesh->positions = malloc((nverts ? nverts : 1) * 3 * sizeof(float));
  mesh->indices = malloc((ntris ? ntris : 1) * 3 * sizeof(unsigned));
  if (!mesh->positions || !mesh->indices) {
    sh_mesh_free(mesh);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory for %s", what);
  }
  mesh->nverts = (int)nverts;
  mesh->ntris = (int)ntris;
  return SH_OK;
}

/* How many times over the distinct files of one load (the mesh and the
 * files it names) assimp may read them, beyond SH__READ_SLACK bytes: an
 * OBJ naming its material library on each of 3000 lines had assimp parse
 * the library 3000 times (60 kB: 8.8 s, by hand), so that the work was
 * the square of the file's size. A load reads its files once or twice,
 * and the first 200 bytes or so of the mesh once for each importer that
 * is asked whether it reads it (16 opens for an STL of an unknown
 * extension). */
#define SH__READ_TIMES 16
#define SH__READ_SLACK (1u << 20)

/* assimp's file system for one load: every file assimp opens (the mesh
 * itself, an OBJ's material library, a glTF's buffers) must resolve inside
 * `root`; the first name refused is kept for the error message. What it
 * reads is counted against the budget above. */
typedef struct confined_fs {
  struct aiFileIO io;
  const char *root;
  char refused[512];
  const char *mesh; /* the mesh's own path */
  char **named;     /* the other files opened, resolved (NULL: not kept) */
  int nnamed, failed, mesh_seen, overread;
  unsigned long long budget, read; /* bytes */
  struct fs_file *open;            /* the files assimp has not closed */
  int obj;                    /* assimp's OBJ importer may read the mesh */
  int mesh_library_checked;   /* the mesh, opened as its own library */
  sh_error library;           /* a material library refused (sh_obj_check.h) */
} confined_fs;

/* One open file: assimp's handle first, so that its callbacks' pointer is
 * this. */
typedef struct fs_file {
  struct aiFile ai;
  confined_fs *fs;
  struct fs_file *next; /* in fs->open */
  int is_mesh;
} fs_file;

/* Whether assimp holds the mesh open. */
static int fs_mesh_open(const confined_fs *fs) {
  for (const fs_file *f = fs->open; f; f = f->next)
    if (f->is_mesh) return 1;
  return 0;
}

/* Checks the material library open as `fp` (sh__mtl_check), `size` bytes,
 * and rewinds it: 0 if refused (the error is kept in fs->library). */
static int fs_library_ok(confined_fs *fs, const char *name, FILE *fp, long long size) {
  char *data = size >= 0 && (unsigned long long)size < SIZE_MAX ? malloc((size_t)size + 1) : NULL;
  if (!data) {
    fs->failed = 1;
    return 0;
  }
  size_t got = fread(data, 1, (size_t)size, fp);
  int ok;
  if (ferror(fp) || fseek(fp, 0, SEEK_SET) != 0) {
    sh_error_set(&fs->library, SH_ERR_IO, "cannot load mesh '%s': cannot read its material "
                 "library '%s'", fs->mesh, name);
    ok = 0;
  } else {
    ok = sh__mtl_check(fs->mesh, name, data, got, &fs->library) == SH_OK;
  }
  free(data);
  return ok;
}

static size_t fs_read(struct aiFile *f, char *buf, size_t size, size_t n) {
  confined_fs *fs = ((fs_file *)(void *)f)->fs;
  unsigned long long want = (unsigned long long)size * n;
  if (size && n > SIZE_MAX / size) return 0;
  if (fs->read + want > fs->budget) {
    fs->overread = 1;
    return 0;
  }
  size_t got = fread(buf, size, n, (FILE *)f->UserData);
  fs->read += (unsigned long long)got * size;
  return got;
}
static size_t fs_write(struct aiFile *f, const char *buf, size_t size,
                       size_t n) {
  (void)f, (void)buf, (void)size, (void)n;
  return 0; /* loading never writes */
}
static size_t fs_tell(struct aiFile *f) {
  long t = ftell((FILE *)f->UserData);
  return t < 0 ? 0 : (size_t)t;
}
static size_t fs_size(struct aiFile *f) {
  FILE *fp = (FILE *)f->UserData;
  long at = ftell(fp), end = 0;
  if (fseek(fp, 0, SEEK_END) == 0) end = ftell(fp);
  fseek(fp, at, SEEK_SET);
  return end < 0 ? 0 : (size_t)end;
}
static enum aiReturn fs_seek(struct aiFile *f, size_t off,
                             enum aiOrigin origin) {
  int whence = origin == aiOrigin_CUR ? SEEK_CUR
               : origin == aiOrigin_END ? SEEK_END
                                        : SEEK_SET;
  return fseek((FILE *)f->UserData, (long)off, whence) == 0 ? aiReturn_SUCCESS
                                                            : aiReturn_FAILURE;
}
static void fs_flush(struct aiFile *f) { (void)f; }

static struct aiFile *fs_open(struct aiFileIO *io, const char *name,
                              const char *mode) {
  confined_fs *fs = (confined_fs *)(void *)io->UserData;
  if (!name || strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+'))
    return NULL;
  if (fs->overread || fs->library.status != SH_OK)
    return NULL; /* the load is refused: no more work */
  /* Outside the tree is refused before missing is said: a missing
   * "../x.bin" is placed by its names (sh__confined_name). */
  char *resolved = NULL;
  int inside = sh__confined_name(name, fs->root, &resolved);
  free(resolved);
  resolved = NULL;
  if (inside == 0) {
    if (!fs->refused[0]) snprintf(fs->refused, sizeof fs->refused, "%s", name);
    return NULL;
  }
  inside = sh__confined(name, fs->root, &resolved);
  if (inside < 0) return NULL; /* does not exist: assimp says so */
  if (inside == 0) { /* moved out since (a link changed): refused as well */
    free(resolved);
    if (!fs->refused[0]) snprintf(fs->refused, sizeof fs->refused, "%s", name);
    return NULL;
  }
  /* Every file other than the mesh itself is kept, for the outputs' check
   * (a render must not overwrite what it reads). */
  char *self = NULL;
  int is_mesh = sh__confined(fs->mesh, fs->root, &self) >= 0 && self &&
                !strcmp(self, resolved);
  free(self);
  int known = is_mesh && fs->mesh_seen;
  for (int i = 0; i < fs->nnamed && !known; i++) known = !strcmp(fs->named[i], resolved);
  int first = !known; /* the first open of this file in the load */
  fs->mesh_seen |= is_mesh;
  if (!known && is_mesh) known = 1; /* the mesh is not kept */
  if (!known) {
    char **nn = realloc(fs->named, (size_t)(fs->nnamed + 1) * sizeof *nn);
    if (!nn) {
      fs->failed = 1;
      free(resolved);
      return NULL;
    }
    fs->named = nn;
    fs->named[fs->nnamed++] = resolved;
  } else {
    free(resolved);
  }
  FILE *fp = sh_file_open_read(name);
  if (!fp) return NULL;
  /* A FIFO or a device inside the tree would block or never end. */
  struct stat sb;
  if (fstat(fileno(fp), &sb) != 0 || !S_ISREG(sb.st_mode)) {
    fclose(fp);
    return NULL;
  }
  /* In an OBJ load, every other file is a material library, and so is
   * the mesh opened again while assimp reads it (a mesh naming itself):
   * checked once each before assimp reads it. */
  if (fs->obj && (!is_mesh || fs_mesh_open(fs)) &&
      (is_mesh ? !fs->mesh_library_checked : first)) {
    fs->mesh_library_checked |= is_mesh;
    if (!fs_library_ok(fs, name, fp, (long long)sb.st_size)) {
      fclose(fp);
      return NULL;
    }
  }
  if (first) fs->budget += SH__READ_TIMES * (unsigned long long)sb.st_size;
  fs_file *ff = calloc(1, sizeof *ff);
  if (!ff) {
    fclose(fp);
    return NULL;
  }
  ff->fs = fs;
  ff->is_mesh = is_mesh;
  ff->next = fs->open;
  fs->open = ff;
  struct aiFile *f = &ff->ai;
  f->ReadProc = fs_read;
  f->WriteProc = fs_write;
  f->TellProc = fs_tell;
  f->FileSizeProc = fs_size;
  f->SeekProc = fs_seek;
  f->FlushProc = fs_flush;
  f->UserData = (aiUserData)(void *)fp;
  return f;
}

static void fs_close(struct aiFileIO *io, struct aiFile *f) {
  (void)io;
  if (!f) return;
  fs_file *ff = (fs_file *)(void *)f;
  for (fs_file **p = &ff->fs->open; *p; p = &(*p)->next)
    if (*p == ff) {
      *p = ff->next;
      break;
    }
  fclose((FILE *)f->UserData);
  free(ff);
}

/* Closes what assimp left open: Debian's assimp 5.2 drops a stream without
 * closing it when an importer throws (an OBJ whose material library is
 * refused by the read budget), which leaked the FILE and its handle (88
 * bytes in core.sh_obj_check_test under LeakSanitizer). Called once the
 * import has returned, when assimp holds no stream any more. */
static void fs_close_all(confined_fs *fs) {
  while (fs->open) fs_close(&fs->io, &fs->open->ai);
}

/* The directory part of path ("." if it has none); caller frees. */
static char *dir_of(const char *path) {
  const char *slash = strrchr(path, '/');
  if (!slash) return strdup(".");
  size_t n = slash == path ? 1 : (size_t)(slash - path);
  char *d = malloc(n + 1);
  if (!d) return NULL;
  memcpy(d, path, n);
  d[n] = '\0';
  return d;
}

/* Whether assimp picks the importer of `path` by what the file holds:
 * assimp 5.2's Importer::ReadFile (code/Common/Importer.cpp at v5.2.5)
 * gives a file to the one importer that lists an extension ending its name
 * (compared without case), whatever the file holds; when none does, or
 * several do (.gltf: the glTF 1 and 2 importers), it asks those, then
 * every importer in turn, whether the file's first bytes look like theirs,
 * so any importer may take it (a .gltf file holding an OFF header went to
 * assimp's OFF importer, which asked for 68 GB: found by fuzz/mesh_fuzz,
 * fuzz/known/gltf_sniffed_off). */
static int assimp_sniffs(const char *path) {
  const sh__assimp *ai = sh__assimp_get(path, NULL);
  if (!ai) return 1;
  size_t len = strlen(path), claimants = 0;
  for (size_t i = 0; i < ai->nformats && claimants < 2; i++) {
    const char *e = ai->format_extensions[i];
    while (*e) { /* a list of extensions, separated by spaces */
      size_t k = strcspn(e, " ");
      if (k && k < len && path[len - k - 1] == '.' && !strncasecmp(path + len - k, e, k)) {
        claimants++;
        break;
      }
      e += k + (e[k] == ' ');
    }
  }
  return claimants != 1;
}

/* The formats the core reads itself, never through assimp (whose
 * readers of them loop forever or allocate what a header declares):
 * sh_ply.h's for a file whose first non-blank bytes are "ply" (all assimp
 * asks), sh_off.h's for a file named *.off or, when assimp picks the
 * importer by the file's bytes (assimp_sniffs), whose first bytes are
 * "off" (all assimp asks then). NULL for any other file. */
typedef sh_status (*own_reader)(const char *path, const char *data, size_t size,
                                sh_mesh *mesh, sh_error *err);

static own_reader own_reader_of(const char *path, const unsigned char *head, size_t n) {
  if (sh__ply_magic(head, n)) return sh__ply_read;
  char ext[16];
  sh_file_extension(path, ext, sizeof ext);
  if (!strcmp(ext, "off")) return sh__off_read;
  return sh__off_magic(head, n) && assimp_sniffs(path) ? sh__off_read : NULL;
}

/* Reads the mesh `path` of `size` bytes whole, after checking that it lies
 * inside `root` (NULL: its own directory), into *data (malloc'ed, with a
 * NUL after its *got bytes). */
static sh_status read_confined(const char *path, const char *root, long long size,
                               char **data, size_t *got, sh_error *err) {
  *data = NULL;
  char *own_root = root ? NULL : dir_of(path);
  if (!root && !own_root) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  int inside = sh__confined(path, root ? root : own_root, NULL);
  if (inside == 0) {
    sh_status st = sh_error_set(
        err, SH_ERR_MESH,
        "the mesh '%s' lies outside the scene's directory '%s': files a scene "
        "uses must lie in its directory tree",
        path, root ? root : own_root);
    free(own_root);
    return st;
  }
  free(own_root);
  FILE *f = sh_file_open_read(path);
  if (!f)
    return sh_error_set(err, SH_ERR_IO, "cannot open mesh '%s': %s", path,
                        strerror(errno));
  *data = size >= 0 && (unsigned long long)size < SIZE_MAX ? malloc((size_t)size + 1) : NULL;
  if (!*data) {
    fclose(f);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory for mesh '%s'", path);
  }
  *got = fread(*data, 1, (size_t)size, f);
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    free(*data);
    *data = NULL;
    return sh_error_set(err, SH_ERR_IO, "cannot read mesh '%s'", path);
  }
  (*data)[*got] = '\0';
  return SH_OK;
}

/* Loads `path` with the core's own reader if it is one of their formats:
 * *handled is set then, and the status is the load's. */
static sh_status load_own(const char *path, const char *root, long long size,
                          sh_mesh *mesh, int *handled, sh_error *err) {
  *handled = 0;
  FILE *f = sh_file_open_read(path);
  if (!f)
    return sh_error_set(err, SH_ERR_IO, "cannot open mesh '%s': %s", path,
                        strerror(errno));
  unsigned char head[64];
  size_t n = fread(head, 1, sizeof head, f);
  fclose(f);
  own_reader read = own_reader_of(path, head, n);
  if (!read) return SH_OK;
  *handled = 1;
  char *data;
  size_t got;
  sh_status st = read_confined(path, root, size, &data, &got, err);
  if (st != SH_OK) return st;
  /* The readers parse numbers with strtod: in the C locale, whatever the
   * program's (sh_mesh_reader.h). */
  locale_t c_locale = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
  if (!c_locale) {
    free(data);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  locale_t old = uselocale(c_locale);
  st = read(path, data, got, mesh, err);
  uselocale(old);
  freelocale(c_locale);
  free(data);
  return st;
}

/* Whether assimp's OBJ importer, asked whether it reads a file, says yes
 * to its first bytes `head` (ObjFileImporter::CanRead at v5.2.5, through
 * BaseImporter::SearchFileHeaderForToken): in the first 200 bytes, NULs
 * dropped and in lower case, the first occurrence of one of its tokens
 * with no letter just before it. */
static int obj_importer_reads(const char *head, size_t n) {
  static const char *const tokens[] = {"mtllib", "usemtl", "v ", "vt ", "vn ",
                                       "o ",     "g ",     "s ", "f "};
  char buf[201];
  size_t k = 0;
  for (size_t i = 0; i < n && i < 200; i++)
    if (head[i]) buf[k++] = (char)tolower((unsigned char)head[i]);
  buf[k] = '\0';
  for (size_t t = 0; t < sizeof tokens / sizeof *tokens; t++) {
    const char *r = strstr(buf, tokens[t]);
    if (r && (r == buf || !isalpha((unsigned char)r[-1]))) return 1;
  }
  return 0;
}

/* Whether the `n` bytes at `data` (NULs among them) hold `word`. */
static int holds(const char *data, size_t n, const char *word) {
  size_t k = strlen(word);
  for (size_t i = 0; i + k <= n; i++)
    if (data[i] == word[0] && !memcmp(data + i, word, k)) return 1;
  return 0;
}

/* The checks of what assimp does not bound (sh_gltf_check.h,
 * sh_obj_check.h), for the files its glTF and OBJ importers could take: by
 * their extensions, or any file whose importer assimp picks by its bytes
 * (assimp_sniffs: then those importers may take it by its first lines).
 * *obj_load tells whether assimp's OBJ importer may read the file and open
 * material libraries: named *.obj, or picked by its bytes, which that
 * importer says it reads, which is not glTF's JSON text, and which holds
 * "mtllib" somewhere (the OBJ importer opens libraries for mtllib lines
 * only). So the files a glTF names (its buffers) are not taken for
 * material libraries, unless a binary glTF holds "mtllib". */
static sh_status check_before_assimp(const char *path, const char *root, long long size,
                                     int *obj_load, sh_error *err) {
  char ext[8];
  sh_file_extension(path, ext, sizeof ext);
  int named_obj = !strcmp(ext, "obj"), sniffed = assimp_sniffs(path);
  int gltf = sh__gltf_candidate(path) || sniffed, obj = named_obj || sniffed;
  *obj_load = named_obj;
  if (!gltf && !obj) return SH_OK;
  char *data;
  size_t got;
  sh_status st = read_confined(path, root, size, &data, &got, err);
  if (st == SH_OK && gltf) st = sh__gltf_check(path, data, got, err);
  if (st == SH_OK && obj) st = sh__obj_check(path, data, got, err);
  if (st == SH_OK && sniffed && !named_obj)
    *obj_load = obj_importer_reads(data, got) && !sh__gltf_json_text(data, got) &&
                holds(data, got, "mtllib");
  free(data);
  return st;
}

static void free_named(char **named, int n) {
  for (int i = 0; i < n; i++) free(named[i]);
  free(named);
}

sh_status sh_mesh_load(const char *path, const char *root, sh_mesh *mesh,
                       sh_error *err) {
  char **named = NULL;
  int n = 0;
  sh_status st = sh__mesh_load_named(path, root, mesh, &named, &n, err);
  free_named(named, n);
  return st;
}

sh_status sh__mesh_load_named(const char *path, const char *root, sh_mesh *mesh,
                              char ***named, int *nnamed, sh_error *err) {
  *named = NULL;
  *nnamed = 0;
  /* assimp reports a missing file like any other failure: tell them apart
   * first. */
  long long size = 0;
  sh_status rs = sh__file_load_begin("sh_mesh_load", "mesh", mesh, sizeof *mesh,
                                     path, &size, err);
  if (rs != SH_OK)
    return rs;
  int handled;
  rs = load_own(path, root, size, mesh, &handled, err);
  if (handled || rs != SH_OK)
    return rs;
  int obj;
  if ((rs = check_before_assimp(path, root, size, &obj, err)) != SH_OK)
    return rs;

  const sh__assimp *ai = sh__assimp_get(path, err);
  if (!ai)
    return SH_ERR_MESH;

  char *own_root = root ? NULL : dir_of(path);
  if (!root && !own_root)
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  confined_fs fs;
  memset(&fs, 0, sizeof fs);
  fs.io.OpenProc = fs_open;
  fs.io.CloseProc = fs_close;
  fs.io.UserData = (aiUserData)(void *)&fs;
  fs.root = root ? root : own_root;
  fs.budget = SH__READ_SLACK;
  fs.mesh = path;
  fs.obj = obj;
  sh_error_init(&fs.library);
  const struct aiScene *scene = ai->import_file_ex(
      path,
      /* ValidateDataStructure first: Debian's assimp is built with its
       * assertions on, and a malformed file (an OFF face with no indices,
       * found by fuzz/mesh_fuzz) made Triangulate abort the process; the
       * validation refuses such data with an error instead. */
      aiProcess_ValidateDataStructure | aiProcess_Triangulate |
          aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
          aiProcess_SortByPType,
      &fs.io);
  fs_close_all(&fs);
  if (fs.failed || fs.refused[0]) sh_error_clear(&fs.library);
  if (fs.failed) {
    if (scene) ai->release_import(scene);
    free_named(fs.named, fs.nnamed);
    free(own_root);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  if (fs.refused[0]) {
    free_named(fs.named, fs.nnamed);
    fs.named = NULL;
    fs.nnamed = 0;
    /* Refused whether or not assimp went on without the file. */
    if (scene) ai->release_import(scene);
    sh_status st = sh_error_set(
        err, SH_ERR_MESH,
        "the mesh '%s' names the file '%s', which lies outside the scene's "
        "directory '%s': files a scene uses must lie in its directory tree (copy "
        "the file into it and change the mesh's reference to it, or remove the "
        "reference)",
        path, fs.refused, fs.root);
    free(own_root);
    return st;
  }
  if (fs.library.status != SH_OK) {
    /* Refused whether or not assimp went on without the library. */
    free_named(fs.named, fs.nnamed);
    if (scene) ai->release_import(scene);
    free(own_root);
    sh_status st = fs.library.status;
    sh_error_move(err, &fs.library);
    return st;
  }
  if (fs.overread) {
    free_named(fs.named, fs.nnamed);
    fs.named = NULL;
    fs.nnamed = 0;
    if (scene) ai->release_import(scene);
    free(own_root);
    return sh_error_set(
        err, SH_ERR_MESH,
        "cannot load mesh '%s': assimp read it and the files it names more than %d "
        "times over (%llu bytes of %llu bytes of files): a file named again and "
        "again, such as one material library on many lines",
        path, SH__READ_TIMES, fs.read,
        (fs.budget - SH__READ_SLACK) / SH__READ_TIMES);
  }
  free(own_root);
  /* The caller owns the list from here, whatever follows. */
  *named = fs.named;
  *nnamed = fs.nnamed;
  if (!scene) {
    const char *msg = ai->get_error_string();
    return sh_error_set(err, SH_ERR_MESH, "cannot load mesh '%s': %s", path,
                        msg && *msg ? msg : "assimp could not read it");
  }

  /* Count the triangles of every mesh; points and lines are skipped. */
  size_t nverts = 0, ntris = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; m++) {
    const struct aiMesh *am = scene->mMeshes[m];
    size_t t = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
      if (am->mFaces[f].mNumIndices == 3)
        t++;
    if (t) {
      nverts += am->mNumVertices;
      ntris += t;
    }
  }
  if (ntris == 0) {
    ai->release_import(scene);
    return sh_error_set(err, SH_ERR_MESH,
                        "cannot load mesh '%s': it has no triangles", path);
  }
  sh_status s = sh__mesh_alloc(mesh, nverts, ntris, path, err);
  if (s != SH_OK) {
    ai->release_import(scene);
    return s;
  }

  size_t v0 = 0, t0 = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; m++) {
    const struct aiMesh *am = scene->mMeshes[m];
    size_t t = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
      const struct aiFace *face = &am->mFaces[f];
      if (face->mNumIndices != 3)
        continue;
      for (int k = 0; k < 3; k++) {
        unsigned idx = face->mIndices[k];
        if (idx >= am->mNumVertices) {
          ai->release_import(scene);
          sh_mesh_free(mesh);
          return sh_error_set(err, SH_ERR_MESH,
                              "cannot load mesh '%s': a face refers to "
                              "vertex %u of %u",
                              path, idx, am->mNumVertices);
        }
        mesh->indices[3 * (t0 + t) + k] = (unsigned)(v0 + idx);
      }
      t++;
    }
    if (!t)
      continue;
    for (unsigned v = 0; v < am->mNumVertices; v++) {
      float *p = mesh->positions + 3 * (v0 + v);
      p[0] = am->mVertices[v].x;
      p[1] = am->mVertices[v].y;
      p[2] = am->mVertices[v].z;
      if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
        ai->release_import(scene);
        sh_mesh_free(mesh);
        return sh_error_set(err, SH_ERR_MESH,
                            "cannot load mesh '%s': vertex %u of mesh %u is "
                            "not a finite number (NaN, infinite or beyond "
                            "single precision's 3.4e38)",
                            path, v + 1, m + 1);
      }
    }
    v0 += am->mNumVertices;
    t0 += t;
  }
  ai->release_import(scene);
  return SH_OK;
}

sh_status sh_mesh_heightfield(const sh_image *img, sh_vec3 bmin, sh_vec3 bmax,
                              sh_mesh *mesh, sh_error *err) {
  if (!mesh)
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_mesh_heightfield was given no mesh");
  memset(mesh, 0, sizeof *mesh);
  if (!img || !img->rgb || img->width < 2 || img->height < 2)
    return sh_error_set(err, SH_ERR_ARG,
                        "a heightfield image needs at least 2x2 pixels");
  if (!(bmin.x < bmax.x && bmin.z < bmax.z && bmin.y <= bmax.y))
    return sh_error_set(err, SH_ERR_ARG,
                        "a heightfield's box needs min < max in x and z and "
                        "min <= max in y");
  int w = img->width, h = img->height;
  size_t nv = (size_t)w * (size_t)h;
  size_t nt = 2 * (size_t)(w - 1) * (size_t)(h - 1);
  sh_status s = sh__mesh_alloc(mesh, nv, nt, "the heightfield", err);
  if (s != SH_OK)
    return s;
  double dx = bmax.x - bmin.x, dy = bmax.y - bmin.y, dz = bmax.z - bmin.z;
  for (int j = 0; j < h; j++)
    for (int i = 0; i < w; i++) {
      const float *px = img->rgb + 3 * ((size_t)j * w + i);
      double grey = sh_clamp((px[0] + (double)px[1] + px[2]) / 3.0, 0.0, 1.0);
      if (grey != grey)
        grey = 0;
      float *p = mesh->positions + 3 * ((size_t)j * w + i);
      p[0] = (float)(bmin.x + (double)i / (w - 1) * dx);
      p[1] = (float)(bmin.y + grey * dy);
      p[2] = (float)(bmin.z + (double)j / (h - 1) * dz);
    }
  /* Cell corners a = (i, j), b = (i+1, j), c = (i, j+1), d = (i+1, j+1):
   * (a, c, b) and (b, c, d) are counter-clockwise seen from +Y. */
  unsigned *t = mesh->indices;
  for (int j = 0; j + 1 < h; j++)
    for (int i = 0; i + 1 < w; i++) {
      unsigned a = (unsigned)(j * w + i), b = a + 1;
      unsigned c = a + (unsigned)w, d = c + 1;
      *t++ = a;
      *t++ = c;
      *t++ = b;
      *t++ = b;
      *t++ = c;
      *t++ = d;
    }
  return SH_OK;
}
