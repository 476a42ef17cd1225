// Quaternions as vec4 (x, y, z, w), w the scalar part.
#ifndef TB_QUAT_GLSL
#define TB_QUAT_GLSL

vec4 quat_mul(vec4 a, vec4 b)
{
    return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz));
}

// The inverse of the unit quaternion q.
vec4 quat_conj(vec4 q)
{
    return vec4(-q.xyz, q.w);
}

// Rotation matrix; its columns are the body's axes in world space.
// v turned by the unit quaternion q.
vec3 quat_rotate(vec4 q, vec3 v)
{
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

mat3 quat_to_mat3(vec4 q)
{
    vec3 q2 = q.xyz * 2.0;
    float xx = q.x * q2.x, yy = q.y * q2.y, zz = q.z * q2.z;
    float xy = q.x * q2.y, xz = q.x * q2.z, yz = q.y * q2.z;
    float wx = q.w * q2.x, wy = q.w * q2.y, wz = q.w * q2.z;
    return mat3(vec3(1.0 - yy - zz, xy + wz, xz - wy),
                vec3(xy - wz, 1.0 - xx - zz, yz + wx),
                vec3(xz + wy, yz - wx, 1.0 - xx - yy));
}

#endif
