/* Example plugin: a radial blast, or a force field while its strength stays set.
 *
 * One GPU stage at the pre-step point accelerates every dynamic body within `radius` of
 * the centre away from it: the strength (m/s^2) at the centre, falling linearly to 0 at the
 * radius (negative strength pulls). Set the parameters with tb_world_set_plugin_param and
 * a tb_blast_params (blast.h); a one-step blast sets the strength for one step, then 0.
 *
 * Built twice: with the stage's SPIR-V inside (BLAST_SPIRV, the header the build makes from
 * blast.comp) and with blast.comp beside the shared object, compiled when it loads.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "blast.h"
#include "tumble_plugin.h"

#ifdef BLAST_SPIRV
#include BLAST_SPIRV
#endif

static int check_params(void* user, const void* block, char* why, size_t why_size)
{
    (void)user;
    tb_blast_params p;
    memcpy(&p, block, sizeof p);
    if (!isfinite(p.centre.x) || !isfinite(p.centre.y) || !isfinite(p.centre.z) ||
        !isfinite(p.centre.w)) {
        snprintf(why, why_size, "centre and strength must be finite");
        return 1;
    }
    if (!isfinite(p.reach.x) || p.reach.x <= 0) {
        snprintf(why, why_size, "radius must be finite and > 0, not %g", (double)p.reach.x);
        return 1;
    }
    return 0;
}

static const tb_blast_params defaults = { { 0, 0, 0, 0 }, { 1, 0, 0, 0 } };

static const tb_plugin_stage stages[] = { {
    .size = sizeof(tb_plugin_stage), .name = "push", .point = TB_PLUGIN_PRE_STEP,
    .dispatch = TB_PLUGIN_PER_BODY,
#ifdef BLAST_SPIRV
    .spirv = blast_spirv, .spirv_size = sizeof blast_spirv,
#else
    .glsl_path = "blast.comp",
#endif
} };

static const tb_plugin plugin = {
    .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION, .name = "blast",
    .param_bytes = sizeof(tb_blast_params), .default_params = &defaults,
    .stage_count = 1, .stages = stages, .check_params = check_params,
};

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;
    return &plugin;
}
