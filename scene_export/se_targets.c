/* The exporters: one row each (se_run.h). A new target is a file with its
 * build function (se_build, se_export.h) and a row here. */
#include "se_blender.h"
#include "se_json.h"
#include "se_pov.h"
#include "se_run.h"

const se_target se_targets[] = {
    {"pov", "pov", se_pov_build,
     "OUT = DIR/NAME.pov: writes NAME.pov, NAME.ini and the light maps "
     "NAME_map<i>.exr; `povray NAME.ini` in DIR renders DIR/NAME.exr (an "
     "atmosphere with Mie scattering, or a Cornette-Shanks phase rendered as "
     "several lobes: frames NAME1.exr, NAME2.exr, ..., whose signed sum is "
     "the image, e.g. oiiotool NAME1.exr NAME2.exr --add NAME3.exr --sub -o "
     "NAME.exr; the .pov's header has the command, the .ini's Frame_Signs "
     "the signs; scene_export prints the commands as its `render:` line)"},
    {"blender", "py", se_blender_build,
     "OUT = DIR/NAME.py: writes NAME.py (a fixed script), its data "
     "NAME.blender.json and light maps NAME_blender_map<i>.exr; render with "
     "blender -b -P DIR/NAME.py -- --engine cycles|eevee --out IMG.exr "
     "[--samples N] [--seed S] [--width W] [--height H] [--one-pass] "
     "(EEVEE needs a display: run it under xvfb-run). Cycles renders a "
     "height fog or atmosphere whose coefficients differ between colour "
     "channels once per channel with grey coefficients and composes the "
     "image (Cycles 3.4 renders such media too dark in one pass); "
     "--one-pass renders it once"},
    {"json", "json", se_json_build,
     "OUT = FILE.json: the normalised scene (defaults filled in, transforms "
     "as matrices, files relative to OUT, copied beside it when outside its "
     "directory)"},
    {NULL, NULL, NULL, NULL},
};
