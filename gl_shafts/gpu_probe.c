/* gl_shafts_gpu_probe: what gpu_check.sh reports before it renders: the
 * devices EGL's device platform lists, then the context gl_shafts gets
 * from a backend (default egl), as lines of "key: value":
 *   devices: N hardware
 *   device 0: hardware, /dev/dri/card0; extensions: ...
 *   backend: egl
 *   renderer: NVIDIA GeForce RTX 3060/PCIe/SSE2
 *   vendor: NVIDIA Corporation
 *   version: 4.6.0 NVIDIA 525.147.05
 *   hardware: yes
 * "hardware: no" when the renderer is one of Mesa's software rasterizers
 * (llvmpipe, softpipe, swrast). Exit status 0 when a context was made
 * (whatever it runs on), 1 when none could be. */
#include <stdio.h>
#include <string.h>

#include "gs_context.h"
#include "sh_cli.h"

static const sh_cli_tool tool = {
    .name = "gl_shafts_gpu_probe",
    .synopsis = "[egl|auto|osmesa]",
    .description = "Lists the devices EGL's device platform sees and the GL "
                   "context gl_shafts gets\nfrom a backend (default egl), as "
                   "lines of \"key: value\" (gpu_check.sh).",
    .max_operands = 1};

int main(int argc, char **argv) {
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, NULL, &parsed);
  if (rc >= 0) return rc;
  const char *name = parsed.noperands ? parsed.operands[0] : "egl";
  gs_backend backend = GS_BACKEND_EGL;
  if (!strcmp(name, "auto")) backend = GS_BACKEND_AUTO;
  else if (!strcmp(name, "osmesa")) backend = GS_BACKEND_OSMESA;
  else if (strcmp(name, "egl")) {
    sh_cli_error(tool.name,
                 "backend: unknown value '%s'; expected one of: egl, auto, "
                 "osmesa",
                 name);
    return SH_EXIT_BAD_INPUT;
  }
  static char devices[16384];
  int hw = gs__egl_devices(devices, sizeof devices);
  printf("devices: %d hardware\n%s", hw < 0 ? 0 : hw, devices);
  gs__context *ctx = NULL;
  sh_error err = SH_ERROR_INIT;
  if (gs__context_create(backend, &ctx, &err) != SH_OK) {
    printf("backend: none\nerror: %s\nhardware: no\n", err.message);
    sh_error_clear(&err);
    return 1;
  }
  const char *r = gs__context_renderer(ctx);
  int software = strstr(r, "llvmpipe") || strstr(r, "softpipe") || strstr(r, "swrast") ||
                 strstr(r, "Software Rasterizer");
  printf("backend: %s\nrenderer: %s\nvendor: %s\nversion: %s\nhardware: %s\n",
         gs__context_backend_name(ctx), r, gs__context_vendor(ctx),
         gs__context_version(ctx), software ? "no" : "yes");
  gs__context_release(ctx);
  gs__context_free(ctx);
  return 0;
}
