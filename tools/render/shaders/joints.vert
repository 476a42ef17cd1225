#version 450
/* Joint overlay: the segments render_joints.c wrote for this frame, one vertex each
 * (LINE_LIST), coloured by the kind of segment; not depth-tested (render_layout.h). */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(set = 0, binding = TR_BIND_JOINT_LINES, std430) readonly buffer JointLines {
    vec4 joint_lines[];
};

layout(location = 0) out vec3 out_color;

void main()
{
    vec4 v = joint_lines[gl_VertexIndex];
    bool gap = v.w > 0.5 * (TR_JOINT_ARM + TR_JOINT_GAP);
    out_color = gap ? vec3(TR_JOINT_GAP_R, TR_JOINT_GAP_G, TR_JOINT_GAP_B) / 255.0
                    : vec3(TR_JOINT_ARM_R, TR_JOINT_ARM_G, TR_JOINT_ARM_B) / 255.0;
    gl_Position = pc.view_proj * vec4(v.xyz, 1.0);
}
