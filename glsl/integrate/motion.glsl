// The turn of a body over a time step, shared by the solver's substeps and the final
// integration.
#ifndef TB_MOTION_GLSL
#define TB_MOTION_GLSL

// For tiny angles sin(a/2)/|w| is replaced by its Taylor series to keep precision.
const float TAYLOR_BELOW = 1e-3;

// The unit quaternion turning by (clamped) angle |w| dt about w.
vec4 rotation_of(vec3 w, float dt, float max_angle)
{
    float speed = length(w);
    float angle = speed * dt;
    float s;   // sin(angle / 2) / speed: scales w into the quaternion's vector part
    if (angle > max_angle) {
        angle = max_angle;
        s = sin(0.5 * angle) / speed;
    } else if (angle < TAYLOR_BELOW) {
        s = 0.5 * dt - dt * dt * dt * speed * speed * (1.0 / 48.0);
    } else {
        s = sin(0.5 * angle) / speed;
    }
    return vec4(w * s, cos(0.5 * angle));
}

// skew(a) b = cross(a, b), column by column (GLSL's mat3 takes columns).
mat3 skew(vec3 a)
{
    return mat3(0.0, a.z, -a.y, -a.z, 0.0, a.x, a.y, -a.x, 0.0);
}

// The gyroscopic term of a torque-free body over a time h: the change of angular velocity
// over h by Euler's equations I dw/dt + w x I w = 0 in the body frame (I: principal moments, w in the
// body frame), by one Newton step on the implicit midpoint rule
//     I (w' - w) + h m x I m = 0,   m = (w + w') / 2,
// started from w' = w. The midpoint rule keeps both the kinetic energy and the length of
// the angular momentum of Euler's equations; the backward Euler step (m = w') loses energy
// and lets the world angular momentum of a spinning 1x2x3 box drift by 3 to 10 % in 10 s.
// Only the change goes back to the world frame, so a spin about a principal axis (no
// change) does not gather the rounding of the turn there and back.
vec3 gyroscopic_change(vec3 w, vec3 inertia, float h)
{
    vec3 Iw = inertia * w;
    vec3 f = h * cross(w, Iw);
    mat3 I = mat3(inertia.x, 0.0, 0.0, 0.0, inertia.y, 0.0, 0.0, 0.0, inertia.z);
    mat3 J = I + 0.5 * h * (skew(w) * I - skew(Iw));
    return -(inverse(J) * f);
}

#endif
