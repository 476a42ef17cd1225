/* Mass properties of a solid convex polyhedron of uniform density, and its principal axes.
 *
 * Volume, first and second moments come from splitting the solid into tetrahedra that share
 * one reference point inside it (each face fanned into triangles), the decomposition used
 * by Mirtich ("Fast and Accurate Computation of Polyhedral Mass Properties", 1996) and
 * Tonon ("Explicit Exact Formulas for the 3-D Tetrahedron Inertia Tensor", 2004). For a
 * tetrahedron with one corner at the origin and the others at a, b, c, with volume
 * V = a . (b x c) / 6, the integral of x x^T over it is
 *     V / 20 * (a a^T + b b^T + c c^T + s s^T),   s = a + b + c.
 * The reference point is the mean of the vertices, so the sums do not cancel large
 * coordinates. Everything is in double, so cglm (float only) is not used here.
 */
#include <math.h>
#include <string.h>

#include "geom/hull_mesh.h"

/* Add tetrahedron (origin, a, b, c) to volume, first moment m1 and second moment m2. */
static void add_tetrahedron(const double a[3], const double b[3], const double c[3],
                            double* volume, double m1[3], double m2[3][3])
{
    double bc[3] = { b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2],
                     b[0] * c[1] - b[1] * c[0] };
    double v = (a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2]) / 6;
    double s[3];
    for (int i = 0; i < 3; i++) s[i] = a[i] + b[i] + c[i];
    *volume += v;
    for (int i = 0; i < 3; i++) {
        m1[i] += v * s[i] / 4;
        for (int j = 0; j < 3; j++)
            m2[i][j] += v / 20 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
    }
}

static void mesh_mean(const tb_hull_mesh* mesh, double r[3])
{
    r[0] = r[1] = r[2] = 0;
    for (uint32_t i = 0; i < mesh->vertex_count; i++)
        for (int k = 0; k < 3; k++) r[k] += mesh->vertices[i][k] / mesh->vertex_count;
}

void tb_hull_mass(const tb_hull_mesh* mesh, double* volume, double center[3],
                  double covariance[3][3])
{
    double r[3], m1[3] = { 0, 0, 0 }, m2[3][3];
    memset(m2, 0, sizeof m2);
    *volume = 0;
    mesh_mean(mesh, r);
    for (uint32_t f = 0; f < mesh->face_count; f++) {
        const uint32_t* loop = mesh->indices + mesh->faces[f].first;
        double p[3][3];
        for (int k = 0; k < 3; k++) p[0][k] = mesh->vertices[loop[0]][k] - r[k];
        for (uint32_t i = 1; i + 1 < mesh->faces[f].count; i++) {
            for (int k = 0; k < 3; k++) {
                p[1][k] = mesh->vertices[loop[i]][k] - r[k];
                p[2][k] = mesh->vertices[loop[i + 1]][k] - r[k];
            }
            add_tetrahedron(p[0], p[1], p[2], volume, m1, m2);
        }
    }
    double c[3];
    for (int i = 0; i < 3; i++) c[i] = *volume > 0 ? m1[i] / *volume : 0;
    /* Parallel axis theorem: second moment about the centre of mass. */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) covariance[i][j] = m2[i][j] - *volume * c[i] * c[j];
    for (int i = 0; i < 3; i++) center[i] = r[i] + c[i];
}

/* One Jacobi rotation in the (p, q) plane that zeroes m[p][q] (Numerical Recipes' form). */
static void jacobi_rotate(double m[3][3], double axes[3][3], int p, int q)
{
    if (m[p][q] == 0) return;
    double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
    double t = (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
    double c = 1 / sqrt(t * t + 1), s = t * c;
    for (int k = 0; k < 3; k++) { /* m = m J */
        double mp = m[k][p], mq = m[k][q];
        m[k][p] = c * mp - s * mq;
        m[k][q] = s * mp + c * mq;
    }
    for (int k = 0; k < 3; k++) { /* m = J^T m */
        double mp = m[p][k], mq = m[q][k];
        m[p][k] = c * mp - s * mq;
        m[q][k] = s * mp + c * mq;
    }
    for (int k = 0; k < 3; k++) { /* axes = axes J */
        double ap = axes[k][p], aq = axes[k][q];
        axes[k][p] = c * ap - s * aq;
        axes[k][q] = s * ap + c * aq;
    }
}

/* Cyclic Jacobi: rotations until the off-diagonal part is negligible. The eigenvectors are
 * the columns of axes; one is flipped if needed so that axes is a proper rotation. */
void tb_sym3_eigen(const double m_in[3][3], double axes[3][3], double values[3])
{
    double m[3][3];
    memcpy(m, m_in, sizeof m);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) axes[i][j] = i == j;
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = fabs(m[0][1]) + fabs(m[0][2]) + fabs(m[1][2]);
        double diag = fabs(m[0][0]) + fabs(m[1][1]) + fabs(m[2][2]);
        if (off <= 1e-17 * diag) break;
        jacobi_rotate(m, axes, 0, 1);
        jacobi_rotate(m, axes, 0, 2);
        jacobi_rotate(m, axes, 1, 2);
    }
    for (int i = 0; i < 3; i++) values[i] = m[i][i];
    double det = axes[0][0] * (axes[1][1] * axes[2][2] - axes[1][2] * axes[2][1]) -
                 axes[0][1] * (axes[1][0] * axes[2][2] - axes[1][2] * axes[2][0]) +
                 axes[0][2] * (axes[1][0] * axes[2][1] - axes[1][1] * axes[2][0]);
    if (det < 0)
        for (int i = 0; i < 3; i++) axes[i][2] = -axes[i][2];
}

/* Shepperd's method: divide by the largest of the four candidates for 4 w^2, 4 x^2, ... */
void tb_mat3_to_quat(const double r[3][3], double q[4])
{
    double tr = r[0][0] + r[1][1] + r[2][2];
    if (tr > r[0][0] && tr > r[1][1] && tr > r[2][2]) {
        double s = 2 * sqrt(1 + tr);
        q[0] = (r[2][1] - r[1][2]) / s; q[1] = (r[0][2] - r[2][0]) / s;
        q[2] = (r[1][0] - r[0][1]) / s; q[3] = s / 4;
    } else if (r[0][0] >= r[1][1] && r[0][0] >= r[2][2]) {
        double s = 2 * sqrt(1 + r[0][0] - r[1][1] - r[2][2]);
        q[0] = s / 4; q[1] = (r[0][1] + r[1][0]) / s;
        q[2] = (r[0][2] + r[2][0]) / s; q[3] = (r[2][1] - r[1][2]) / s;
    } else if (r[1][1] >= r[2][2]) {
        double s = 2 * sqrt(1 + r[1][1] - r[0][0] - r[2][2]);
        q[0] = (r[0][1] + r[1][0]) / s; q[1] = s / 4;
        q[2] = (r[1][2] + r[2][1]) / s; q[3] = (r[0][2] - r[2][0]) / s;
    } else {
        double s = 2 * sqrt(1 + r[2][2] - r[0][0] - r[1][1]);
        q[0] = (r[0][2] + r[2][0]) / s; q[1] = (r[1][2] + r[2][1]) / s;
        q[2] = s / 4; q[3] = (r[1][0] - r[0][1]) / s;
    }
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int i = 0; i < 4; i++) q[i] /= len;
}
