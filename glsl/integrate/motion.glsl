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

#endif
