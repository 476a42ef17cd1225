#version 450
#extension GL_GOOGLE_include_directive : require
// The blast plugin's stage (pre-step, one thread per body): every dynamic body within the
// radius is accelerated away from the centre, by the strength at the centre falling off
// linearly to nothing at the radius (tb_blast_params).
#include "tumble_plugin.glsl"
#include "blast.h"

void main()
{
    if (!tb_plugin_begin()) return;
    uint i = tb_plugin_thread_index();
    if (i >= tb_plugin_body_count() ||
        !tb_plugin_body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC))
        return;
    tb_blast_params blast = tb_blast_params(tb_plugin_param(0u), tb_plugin_param(1u));
    float radius = blast.reach.x;
    vec3 away = body_pos[i].xyz - blast.centre.xyz;
    float distance = length(away);
    if (distance >= radius || distance < 1e-6) return;
    float acceleration = blast.centre.w * (1.0 - distance / radius);
    body_linvel[i].xyz += away / distance * (acceleration * tb_plugin_dt());
}
