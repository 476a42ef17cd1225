/* The one layout of GPU data, included by the C core and by every shader.
 *
 * Everything the GPU reads or writes is declared here once: structs, binding indices,
 * specialization constant ids, stage ids, flags. Members are vec4-sized so std140, std430
 * and C agree without padding rules; tests/test_layout.c checks sizes and offsets from C.
 *
 * Bodies are stored as a structure of arrays of vec4, one storage buffer per array, so a
 * stage touches only the arrays it needs and each read is one 16-byte load.
 */
#ifndef TB_LAYOUT_H
#define TB_LAYOUT_H

#if defined(__STDC__) || defined(__cplusplus)
/* ---- C side ---- */
#include <stdint.h>
typedef struct tb_gpu_vec4 { float x, y, z, w; } tb_gpu_vec4;
typedef struct tb_gpu_uvec4 { uint32_t x, y, z, w; } tb_gpu_uvec4;
#define TB_VEC4 tb_gpu_vec4
#define TB_UVEC4 tb_gpu_uvec4
#define TB_STRUCT(name) typedef struct name name; struct name
#define TB_U(x) x##u
#else
/* ---- GLSL side ---- */
#define TB_VEC4 vec4
#define TB_UVEC4 uvec4
#define TB_STRUCT(name) struct name
#define TB_U(x) uint(x)
#endif

/* Descriptor set 0: the world. Binding indices. */
#define TB_BIND_PARAMS          0  /* uniform tb_gpu_params */
#define TB_BIND_BODY_POS        1  /* vec4[]: xyz position of the centre (m), w inverse mass (0 static) */
#define TB_BIND_BODY_ROT        2  /* vec4[]: orientation quaternion (x, y, z, w) */
#define TB_BIND_BODY_LINVEL     3  /* vec4[]: xyz linear velocity (m/s), w linear damping (1/s) */
#define TB_BIND_BODY_ANGVEL     4  /* vec4[]: xyz angular velocity (rad/s), w angular damping (1/s) */
#define TB_BIND_BODY_INV_INERTIA 5 /* vec4[]: xyz inverse principal inertia, body frame; w gravity scale */
#define TB_BIND_BODY_INFO       6  /* uvec4[]: x shape index, y TB_BODY_FLAG_*, z its rank in
                                       the joint graph's colouring (src/world/joint_ranks.c),
                                       w reserved */
#define TB_BIND_BODY_AABB_MIN   7  /* vec4[]: world AABB minimum corner, w unused */
#define TB_BIND_BODY_AABB_MAX   8  /* vec4[]: world AABB maximum corner, w unused */
#define TB_BIND_SHAPES          9  /* tb_gpu_shape[] */
#define TB_BIND_COUNTERS        10 /* tb_gpu_counters: counts only the GPU knows, flags, indirect args */
/* Per body slot, GPU-only (sized by the body capacity): */
#define TB_BIND_BODY_PAIRS      11 /* uvec4[]: owned pairs, x offset y count (even steps), z offset w count (odd) */
#define TB_BIND_SOLVER_BODIES   12 /* tb_gpu_solver_body[]: each body as the contact solver works on
                                      it; apply_forces fills it, integrate moves the body by it */
#define TB_BIND_BODY_CLAIM      13 /* uint[]: graph colouring claim of each body */
#define TB_BIND_BODY_PAIR_COUNT 14 /* uint[]: pairs each body owns this step; scanned in place to offsets */
/* Broadphase grid (sized by the body capacity): */
#define TB_BIND_GRID_KEYS       15 /* uint[]: cell hash of each entry, sorted ascending */
#define TB_BIND_GRID_BODIES     16 /* uint[]: body of each entry, sorted with the keys */
#define TB_BIND_GRID_TABLE      17 /* uvec2[]: per hash bucket, [start, end) into the sorted entries */
#define TB_BIND_LARGE_FLAGS     18 /* uint[]: 1 for a static body too large for the grid */
#define TB_BIND_LARGE_LIST      19 /* uint[]: bodies flagged large, in slot order */
/* Pairs (sized by the pair capacity; the two halves alternate by step parity): */
#define TB_BIND_PAIRS           20 /* uvec4[2 * pair cap]: x body a (owner), y body b, z colour, w unused */
#define TB_BIND_COLOUR_LIST     21 /* uint[pair cap]: pair indices (within the half) grouped by colour */
/* Convex hulls (sized by the hull data of the live shapes; tb_gpu_shape.hull locates a hull): */
#define TB_BIND_HULL_VECTORS    22 /* vec4[]: each hull's vertices (xyz, w 0), then its face planes
                                      (xyz outward unit normal, w offset: dot(n, x) = w on the face) */
#define TB_BIND_HULL_TOPOLOGY   23 /* uint[]: each hull's edges (2 uints each: v0 | v1 << 16, then
                                      f0 | f1 << 16: the faces left and right of v0 -> v1 seen from
                                      outside), then its vertex rings (a head per vertex, first |
                                      count << 16 counted from the entries that follow the heads;
                                      an entry per edge end, neighbour | edge << 16), then its
                                      faces (first | count << 16: the face's vertex indices at
                                      topology[face base + first ...], counter-clockwise seen from
                                      outside), then those indices */
#define TB_BIND_COLOUR_WORK     24 /* uint[2 * pair cap]: the constraints still uncoloured, two lists
                                      (each pair cap long) the colouring passes read and
                                      write in turn (tb_gpu_counters.colouring counts them).
                                      Before the solver, in the narrowphase, the first list
                                      is the round pairs grouped by kind
                                      (narrowphase/round_order: those round_cull leaves to
                                      round_points); the second each pair's kind, from
                                      round_cull for round_order */
/* The contact arrays, the largest of the step (about 1,000 bytes per pair), are no bindings:
 * shaders reach them through the device addresses in tb_gpu_params.contact_arrays, so no
 * descriptor range (maxStorageBufferRange: 128 MiB on lavapipe, 4 GiB on NVIDIA) limits how
 * many pairs a step can hold; memory does (world.glsl names them like arrays):
 *   manifolds       tb_gpu_manifold[pair cap]: this step's, indexed like its pairs
 *   prev_manifolds  tb_gpu_manifold[pair cap]: last step's, indexed like its pairs (the
 *                   other half); the warm start reads them. The two arrays trade places
 *                   after every step (the host sets them by the step's parity, and the
 *                   step's command buffer swaps their addresses at its end), so this
 *                   step's manifolds become last step's where they lie
 *   constraints     tb_gpu_constraint[pair cap]: solver data of this step
 *   block_entries   uvec2[8 * pair cap + 2 * joint cap], only in a world that uses the block
 *                   solver: the contact lists of its dynamic bodies, an entry per contact
 *                   point and per joint, grouped by body (block_start): x pair index << 2 |
 *                   point (a joint's: its slot | TB_BLOCK_JOINT) | TB_BLOCK_SIDE_B when the
 *                   body is the pair's (joint's) body b, y the body at the other end */
#define TB_BIND_PLUGIN_PARAMS   25 /* vec4[TB_MAX_PLUGINS * TB_PLUGIN_PARAM_VEC4S]: each loaded
                                      plugin's parameter block (abi/tumble_plugin.h), the host's
                                      copy uploaded before a submission when it changed */
/* The block solver (glsl/block/, src/solver/block.c), per body slot: */
#define TB_BIND_BLOCK_START     26 /* uint[]: first entry of each dynamic body's contact list in
                                      block_entries (counts, scanned in place) */
#define TB_BIND_BLOCK_FILL      27 /* uint[]: entries of each body's list (filled by atomics, then
                                      sorted so the order is the pairs') */
#define TB_BIND_BODY_COLOUR     28 /* uint[]: each dynamic body's colour | the colouring round that
                                      gave it << 8 (TB_BLOCK_NO_COLOUR: none yet); a body the
                                      colouring left to the tail: TB_MAX_COLOURS | its place
                                      in the tail << 8 */
#define TB_BIND_BLOCK_LIST      29 /* uvec4[]: dynamic bodies grouped by colour (counters.colour),
                                      then the tail's (counters.colouring.z of them): x the
                                      body, y its first entry, z its entry count, so a sweep
                                      finds its list with one load; w unused */
#define TB_BIND_BLOCK_TARGET    30 /* vec4[2 * body cap], only in a world that uses the block
                                      solver: each body's free motion over the step (its
                                      delta_position, delta_rotation without contacts), the
                                      pose its inertia pulls it towards */
#define TB_BIND_COUNT           31

/* Specialization constant ids, set for every pipeline. */
#define TB_SPEC_WORKGROUP_SIZE  0  /* local_size_x */
#define TB_SPEC_SUBGROUP_SIZE   1  /* the device's subgroup size: 8 lavapipe, 32 NVIDIA, 64 AMD */
#define TB_SPEC_CPU_DEVICE      2  /* 1 on a CPU implementation (lavapipe), else 0 */

/* Reasons the GPU abandoned a step (tb_gpu_counters.state.x). A stage that sees any flag
 * does nothing, so the bodies keep the state they had before the step; the host grows
 * what overflowed and runs the step again. */
#define TB_ABORT_PAIRS          TB_U(1)   /* more pairs than the pair capacity */
#define TB_ABORT_COLOURS        TB_U(2)   /* constraints (or, for the block solver, bodies)
                                             left uncoloured by the recorded rounds */
#define TB_ABORT_EVENTS         TB_U(4)   /* more contact events than the event capacity */
#define TB_ABORT_ROUNDS         TB_U(8)   /* the block solver: bodies left uncoloured by the
                                             recorded colouring rounds, within the recorded
                                             colours (the host records more rounds) */

/* Graph colouring: at most this many colours (rounds). Claims pack the round into the top
 * bits and a permutation of the constraint index into the low TB_COLOUR_INDEX_BITS. */
#define TB_MAX_COLOURS          64
#define TB_COLOUR_INDEX_BITS    26
#define TB_MAX_PAIR_CAPACITY    (TB_U(1) << TB_COLOUR_INDEX_BITS)
#define TB_NO_COLOUR            TB_U(0xffffffff)

#define TB_MAX_MANIFOLD_POINTS  4

/* tb_gpu_body info.y */
#define TB_BODY_FLAG_ALIVE      TB_U(1)
#define TB_BODY_FLAG_DYNAMIC    TB_U(2)
#define TB_BODY_FLAG_MESH       TB_U(4)   /* its shape is made of triangles (a mesh or a
                                             heightfield): every broadphase treats it as a
                                             large static body, and its pairs are split into
                                             one per triangle (midphase) */
#define TB_BODY_FLAG_COMPOUND   TB_U(8)   /* its shape is a compound: its pairs are split into
                                             one per child (and triangle) */
#define TB_BODY_FLAG_ISOLATED   TB_U(16)  /* its state stopped being finite in a step: the
                                             step cleared ALIVE and DYNAMIC (integrate), so
                                             nothing meets or moves it any more */

/* tb_gpu_shape info.x; equal to tb_shape_type in tumble.h */
#define TB_GPU_SHAPE_SPHERE     TB_U(0)
#define TB_GPU_SHAPE_BOX        TB_U(1)
#define TB_GPU_SHAPE_PLANE      TB_U(2)
#define TB_GPU_SHAPE_HULL       TB_U(3)
#define TB_GPU_SHAPE_MESH       TB_U(4)
#define TB_GPU_SHAPE_HEIGHTFIELD TB_U(5)
#define TB_GPU_SHAPE_COMPOUND   TB_U(6)
#define TB_GPU_SHAPE_CAPSULE    TB_U(7)
#define TB_GPU_SHAPE_CYLINDER   TB_U(8)
#define TB_GPU_SHAPE_CONE       TB_U(9)

/* Convex hull limits: the GPU walks vertices, faces and edges per pair and clips an incident
 * face polygon in registers, so their sizes are bounded. tb_shape_create_hull rejects hulls
 * beyond them with a clear error. */
#define TB_HULL_MAX_VERTICES      256
#define TB_HULL_MAX_FACES         256
#define TB_HULL_MAX_FACE_VERTICES 32

/* Half extent given to unbounded shapes (planes): large, yet its square stays finite. */
#define TB_UNBOUNDED_EXTENT     1.0e18

/* Threads per workgroup of per-body stages. */
#define TB_WORKGROUP_SIZE       64
/* Threads per workgroup of narrowphase/round_cull and round_points
 * (counters.wide_pair_dispatch): when round_points' threads needed about 250 registers, it
 * took 14 % less time in groups of 256 than of 64 on an H100 (groups of 512 capped the
 * registers at 128 and spilled: slower); it needs 128 now. */
#define TB_WIDE_WORKGROUP_SIZE  256
/* Kinds of pairs, as narrowphase/round_order groups them while round shapes live: of the
 * pairs with a capsule, cylinder or cone, for round_points, the shapes' kind (the other
 * shape's TB_GPU_SHAPE_* times 3 plus the round shape's: capsule 0, cylinder 1, cone 2; under
 * 30) times TB_GJK_BUCKETS plus the bucket of the GJK supports the pair took last step, so
 * that a warp's GJK loops run about as long; then contacts.comp's, those with a hull and the
 * others (sphere, box, plane). */
#define TB_GJK_BUCKETS          8
#define TB_ROUND_KINDS          242
#define TB_PAIR_KIND_HULL       TB_U(240)
#define TB_PAIR_KIND_CONVEX     TB_U(241)
/* Threads per workgroup of solver/solve: colour_finish writes counters.colour_dispatch for it. */
#define TB_SOLVER_WORKGROUP_SIZE 64
#define TB_BLOCK_TAIL_WORKGROUP_SIZE 256   /* block/solve_tail: one workgroup, all of it a body */
/* Indirect dispatch arguments the GPU writes keep workgroups in x within Vulkan's guaranteed
 * maxComputeWorkGroupCount[0]; more get rows in y (index = (group.y * num_groups.x +
 * group.x) * size + local). */
#define TB_DISPATCH_MAX_X       65535

/* Parameters of the step, written by the host before a submission (never mid-step). */
TB_STRUCT(tb_gpu_params) {
    TB_VEC4 gravity;        /* xyz gravity (m/s^2), w time step dt (s) */
    TB_UVEC4 counts;        /* x body slots in use (high-water mark), y shape count, z solver
                               substeps, w bodies created and destroyed since the world began
                               (a change says the set of bodies changed) */
    TB_VEC4 limits;         /* x largest rotation per step (rad), y cos of half the turn a
                               pair may make and keep its manifold (tb_world_set_contact_reuse),
                               z w reserved */
    TB_UVEC4 body_dispatch; /* xyz: VkDispatchIndirectCommand covering counts.x bodies; w reserved */
    TB_UVEC4 capacity;      /* x pair capacity (one half), y grid table mask (size - 1),
                               z colouring rounds recorded, w solver iterations */
    TB_VEC4 contact;        /* x contact margin (m), y restitution threshold (m/s),
                               z fastest push-out speed (m/s), w how far a pair may move
                               and keep its manifold (m; below 0: never) */
    TB_VEC4 soft;           /* soft contact of one substep: x bias rate (1/s), y mass scale,
                               z impulse scale, w substep h (s) */
    TB_VEC4 soft_static;    /* the same against a static body: twice as stiff */
    TB_UVEC4 contact_arrays[2]; /* device addresses as (low, high) pairs: [0].xy manifolds,
                                   [0].zw prev_manifolds, [1].xy constraints, [1].zw
                                   block_entries */
    TB_VEC4 block;          /* the block solver's contacts (tb_block_settings): x starting
                               stiffness, y its growth per metre of error, z largest stiffness
                               (all in units of the contact's effective mass / dt^2), w the share
                               of last step's force a contact starts from */
    TB_VEC4 block_more;     /* x the share of a step's starting penetration left for later
                               steps (stabilisation), y 1 when friction counts from where a
                               point began to stick (0: from the step's start), z the pieces
                               the free motion of a step is predicted in (the substeps),
                               w the share of last step's
                               stiffness a contact starts from (a pair's stiffness is carried
                               in tb_gpu_manifold.axis.w) */    TB_UVEC4 joint_arrays;  /* device addresses as (low, high) pairs: xy the joints
                               (tb_gpu_joint[]), zw their state (tb_gpu_joint_state[]) */
    TB_UVEC4 joint_info;    /* x joint slots in use (high-water mark), y entries of the table
                               of body pairs whose joints keep them from colliding (a power of
                               two; 0: no such joint), zw that table's address (uvec2[]: the
                               two body slots + 1, lower first; (0, 0) an empty entry) */
    TB_VEC4 block_joints;   /* the block solver's joints (tb_block_settings): x their largest
                               stiffness (in units of their bodies' effective mass, or moment,
                               / dt^2), y the share of last step's multipliers a joint starts
                               from, z the share of its stiffness, w reserved */
};
#define TB_PARAMS_BODY_DISPATCH_OFFSET 48 /* byte offset of body_dispatch */

/* Counts only the GPU knows. Reset by the step's first stage, except state.x (abort flags,
 * cleared by the host before a submission) and state.y (steps completed). */
TB_STRUCT(tb_gpu_counters) {
    TB_UVEC4 pair_dispatch;   /* xyz: VkDispatchIndirectCommand over this step's pairs */
    TB_UVEC4 state;           /* x TB_ABORT_* flags, y steps completed on the GPU (parity = y & 1),
                                 z pairs this step, w pairs needed (valid after an overflow) */
    TB_UVEC4 grid;            /* x largest dynamic AABB extent (float bits), y large bodies,
                                 z entries sorted (body slots), w the midphase split's sum of
                                 pairs, then the broadphase's records (glsl/midphase/split.glsl) */
    TB_UVEC4 solver;          /* x colours used, y constraints left uncoloured (colouring round 0
                                 counts every constraint here, colour_finish subtracts the
                                 coloured ones), z batches (subgroup-wide), w contact points */
    TB_UVEC4 colouring;       /* x y the lengths of colour work lists 0 and 1, z the constraints
                                 left to solve_tail (listed in work list 0; the block solver:
                                 the bodies of its tail), w the block solver: 1 + the last
                                 colouring round that coloured a body (block/list) */
    TB_UVEC4 colour[TB_MAX_COLOURS];          /* x constraints of the colour, y first index in the
                                                 colour list, z batches before the colour, w unused */
    TB_UVEC4 colour_dispatch[TB_MAX_COLOURS]; /* xyz: VkDispatchIndirectCommand over the colour */
    TB_UVEC4 plugins;         /* x y: 1 + the step count (state.y) whose pre-step (x) and
                                 post-broadphase (y) plugin stages have run: a step abandoned
                                 after them and run again must not run them twice (step/plugin_mark) */
    TB_UVEC4 events;          /* contact events (narrowphase/events): x written so far in this
                                 submission, y written by its completed steps (the host reads
                                 those and zeroes x and y before a submission), z pairs of the
                                 last completed step (its manifolds are prev_manifolds), w unused */
    TB_UVEC4 wide_pair_dispatch; /* xyz: as pair_dispatch, in workgroups of TB_WIDE_WORKGROUP_SIZE */
    TB_UVEC4 round_kinds[TB_ROUND_KINDS]; /* the pairs of each kind (TB_ROUND_KINDS) listed by
                                 narrowphase/round_order: x how many, y placed so far, z
                                 where they start (the round kinds first, so
                                 [TB_PAIR_KIND_HULL].z is how many round pairs
                                 narrowphase/round_cull leaves to round_points), w unused */
    TB_UVEC4 hull_sat;        /* x the hull pairs narrowphase/contacts listed for
                                 narrowphase/hull_sat (in colour_work's second list), yzw
                                 unused */
    TB_UVEC4 guard;           /* x bodies isolated since the world began (integrate: their
                                 state stopped being finite; never cleared), yzw unused */
};
#define TB_COUNTERS_PAIR_DISPATCH_OFFSET 0
#define TB_COUNTERS_COLOUR_DISPATCH_OFFSET (80 + 16 * TB_MAX_COLOURS)
#define TB_COUNTERS_WIDE_PAIR_DISPATCH_OFFSET (112 + 32 * TB_MAX_COLOURS)

/* Joints (src/joints/, glsl/block/joint.glsl): solved by the block solver beside the
 * contacts, as rows of each body's Newton step. A joint's frame is given in each body's
 * frame (the centre-of-mass principal frame); its x axis is a hinge's axis. */
#define TB_GPU_JOINT_NONE       TB_U(0)   /* a free slot (tb_gpu_joint.info.z) */
#define TB_GPU_JOINT_BALL       TB_U(1)
#define TB_GPU_JOINT_HINGE      TB_U(2)
#define TB_GPU_JOINT_FIXED      TB_U(3)
#define TB_GPU_JOINT_DISTANCE   TB_U(4)
#define TB_GPU_JOINT_SLIDER     TB_U(5)
#define TB_GPU_JOINT_CONE       TB_U(6)
#define TB_GPU_JOINT_SIX_DOF    TB_U(7)
#define TB_GPU_JOINT_LIMIT      TB_U(0x100) /* flags, beside the kind: the limit is on */
#define TB_GPU_JOINT_MOTOR      TB_U(0x200) /* the motor is on */
#define TB_GPU_JOINT_SPRING     TB_U(0x400) /* a spring (distance: to the rest length instead of
                                               a rod; hinge, slider: to the target) */
#define TB_GPU_JOINT_BREAKABLE  TB_U(0x800) /* breaks past motor.zw */
/* A 6-dof joint's axis i (0-2 along A's axes, 3-5 turns about them) is locked, free or
 * limited (tb_joint_axis_mode's values): two bits of info.z from
 * TB_GPU_JOINT_AXIS_SHIFT + 2 i. The kinds above are tb_joint_kind's. */
#define TB_GPU_JOINT_AXIS_SHIFT   12
#define TB_GPU_JOINT_AXIS_LOCKED  TB_U(0)
#define TB_GPU_JOINT_AXIS_FREE    TB_U(1)
#define TB_GPU_JOINT_AXIS_LIMITED TB_U(2)
#define TB_GPU_JOINT_SOFT       TB_U(0x1000000) /* its held rows are springs (lower.w Hz,
                                                   upper.w damping ratio) */
/* The slot of the filter table where the pair of body slots + 1 (lo < hi) is first looked
 * for; the next ones follow. */
#define TB_JOINT_FILTER_HASH(lo, hi) \
    (((lo) * TB_U(0x9E3779B1)) ^ (((hi) + TB_U(0x7F4A7C15)) * TB_U(0x85EBCA77)))
TB_STRUCT(tb_gpu_joint) {
    TB_UVEC4 info;            /* x body a slot, y body b slot, z kind | TB_GPU_JOINT_* flags,
                                 w the joint's generation (a reused slot starts its state
                                 anew when it differs from the state's) */
    TB_VEC4 anchor_a;         /* xyz the joint's point in a's frame (m), w what a spring pulls
                                 to: a distance joint's rest length (m), a hinge's angle (rad),
                                 a slider's offset (m) */
    TB_VEC4 anchor_b;         /* xyz in b's frame, w spring frequency (Hz) */
    TB_VEC4 frame_a;          /* quaternion: the joint frame in a's frame */
    TB_VEC4 frame_b;          /* in b's frame: the joint holds both frames together */
    TB_VEC4 limit;            /* x lower, y upper (rad for a hinge's or cone's twist, m for a
                                 slider or a distance joint), z spring damping ratio, w the
                                 cone's half angle (rad) */
    TB_VEC4 motor;            /* x target speed (rad/s, m/s), y most force or torque (N, N m),
                                 z break force (N), w break torque (N m) */
    TB_VEC4 lower;            /* 6-dof: xyz the lower limits of the offset along A's axes (m),
                                 w a soft joint's frequency (Hz) */
    TB_VEC4 upper;            /* xyz their upper limits, w a soft joint's damping ratio */
    TB_VEC4 turn_lower;       /* xyz the lower limits of the turn about A's axes (rad: the
                                 rotation vector of A^-1 B), w unused */
    TB_VEC4 turn_upper;       /* xyz their upper limits, w unused */
};
/* What the GPU keeps of a joint from step to step, and what the host reads of it. */
TB_STRUCT(tb_gpu_joint_state) {
    TB_VEC4 linear;           /* xyz the multipliers of the point rows (ball, hinge, fixed,
                                 cone: the force on b along the world axes, N; slider: x y
                                 along A's y and z axes; 6-dof: along A's axes), w their
                                 stiffness (N/m) */
    TB_VEC4 angular;          /* xyz the multipliers of the angular rows (the torque on b
                                 about the world axes, N m; 6-dof: about A's axes), w their
                                 stiffness (N m/rad) */
    TB_VEC4 axial;            /* x the limit's (a distance joint's, a cone's twist limit's)
                                 multiplier, signed along the axis, y its stiffness, z the
                                 motor's (a cone's swing limit's), w its stiffness */
    TB_VEC4 held_force;       /* a ball, hinge or weld whose force is about its bodies' weights
                                 (block/joint_start): xyz the force on b its point rows ended
                                 last step with (N, world), which the step predicts its bodies'
                                 motion with (block/guess), the rows' multipliers then finding
                                 only the change; w 1 while it does so. Zero otherwise */
    TB_VEC4 held_torque;      /* xyz likewise its angular rows' torque on b (N m, world) */
    TB_VEC4 force;            /* xyz all the force the joint put on b in the last step (N,
                                 world), w unused */
    TB_VEC4 torque;           /* xyz all its torque on b about b's anchor (N m, world) */
    TB_UVEC4 info;            /* x the generation of the joint this state is of, y 1 once
                                 broken, z a bit for each limit engaged (it pushed last step
                                 or in this one: bit 0 the limit of axial.x, 1 a cone's swing;
                                 6-dof: bit i axis i), w unused */
    TB_VEC4 start_error[2];   /* the values of the joint's hard equality rows where the step
                                 began (block/joint_start), in the order joint_rows takes them:
                                 the step's first sweeps hold each row at this value
                                 (block/joint.glsl, joint_hold) */
};

/* A body as the contact solver sees it, in one 96-byte record so a constraint touches three
 * 32-byte sectors per body instead of one per array (velocities, push, pose, inertia, flags),
 * with the world-space inverse inertia worked out once per step instead of per constraint.
 * Bodies that are not dynamic have zero inverse mass and inertia and are never written. */
TB_STRUCT(tb_gpu_solver_body) {
    TB_VEC4 linear;           /* xyz velocity (m/s), w inverse mass (1/kg) */
    TB_VEC4 angular;          /* xyz angular velocity (rad/s), w gravity scale */
    TB_VEC4 delta_position;   /* xyz how far the substeps have moved the centre (m), w unused */
    TB_VEC4 delta_rotation;   /* the rotation the substeps have turned it by (quaternion) */
    TB_VEC4 inv_inertia_diag; /* world inverse inertia tensor: xx, yy, zz; w unused */
    TB_VEC4 inv_inertia_off;  /* xy, xz, yz; w unused */
};

/* The block solver: entries of a body's contact list, and its colouring. */
#define TB_BLOCK_SIDE_B         TB_U(0x80000000)
#define TB_BLOCK_JOINT          TB_U(0x40000000)   /* a joint's entry: its slot | this | side */
#define TB_BLOCK_NO_COLOUR      TB_U(0xffffffff)
#define TB_BLOCK_NOT_SOLVED     TB_U(0xfffffffe)   /* not dynamic: never coloured nor solved */

/* The block solver's sweeps (tb_gpu_push.args.y of block/solve and its variants): bits of what
 * the sweep is. In block/solve_fused args.y holds the sweeps (low 16 bits) and how many of
 * them hold the joints (the high 16). */
#define TB_BLOCK_SWEEP_LAST  TB_U(1) /* the step's last sweep */
#define TB_BLOCK_SWEEP_HOLDS TB_U(2) /* a joint's hard rows hold the error the step began with */
#define TB_BLOCK_FUSED_HOLDS_SHIFT 16
/* The bits of sweep `sweep` of `sweeps`, the first `holds` of them holding the joints. */
#define TB_BLOCK_SWEEP_BITS(sweep, sweeps, holds)                                             \
    (((sweep) + 1u == (sweeps) ? TB_BLOCK_SWEEP_LAST : 0u) |                                  \
     ((sweep) < (holds) ? TB_BLOCK_SWEEP_HOLDS : 0u))

/* Solver sweeps (tb_gpu_push.args.z of solver/solve): what a sweep over the colours does. */
#define TB_SOLVE_BIAS           TB_U(0) /* solve with the soft push-out of penetration */
#define TB_SOLVE_WARM           TB_U(1) /* apply the accumulated impulses (warm start) */
#define TB_SOLVE_RELAX          TB_U(2) /* solve without push-out: remove its velocity */
#define TB_SOLVE_RESTITUTION    TB_U(3) /* after the substeps: bounce */

/* Push constants of the world's stages that take them (the solver's colour and iteration). */
TB_STRUCT(tb_gpu_push) {
    TB_UVEC4 args;            /* x colour (or round), y iteration (or sub-round), z flags (or
                                 sub-rounds), w colouring pass (its parity picks the work list) */
};

/* Plugins (abi/tumble_plugin.h, abi/tumble_plugin.glsl): the points of the step where their
 * stages run (the values of tb_plugin_point), their parameter blocks and push constants. */
#define TB_PLUGIN_POINT_PRE_STEP        TB_U(0)
#define TB_PLUGIN_POINT_POST_BROADPHASE TB_U(1)
#define TB_PLUGIN_POINT_POST_SOLVE      TB_U(2)
#define TB_PLUGIN_POINT_POST_STEP       TB_U(3)
#define TB_PLUGIN_POINT_COUNT           4
#define TB_MAX_PLUGINS          16
#define TB_PLUGIN_PARAM_VEC4S   16   /* a parameter block: 256 bytes */
TB_STRUCT(tb_gpu_plugin_push) {
    TB_UVEC4 args;            /* x the plugin's first vec4 in plugin_params, y the point
                                 (TB_PLUGIN_POINT_*), z the stage's index in the plugin, w unused */
};

/* A pair of bodies whose contact began or ended in a step (narrowphase/events, for plugins'
 * host callbacks): a pair is in contact when its manifold has points. */
TB_STRUCT(tb_gpu_contact_event) {
    TB_UVEC4 info;            /* x TB_EVENT_BEGIN or _END, y body a, z body b, w the step
                                 (counters.state.y while it ran) */
    TB_VEC4 point;            /* xyz the pair's first point, w its point count */
    TB_VEC4 normal;           /* xyz from a to b, w normal impulse of the step, summed over the
                                 points (for an end: of the last step it touched) */
    TB_VEC4 friction;         /* xyz friction impulse of the step, world frame, summed; w unused */
};
#define TB_EVENT_BEGIN          TB_U(0)
#define TB_EVENT_END            TB_U(1)
/* Push constants of narrowphase/events: args x the pass (TB_EVENTS_*), y the event capacity;
 * address xy the events (tb_gpu_contact_event[capacity]), zw the match marks (uint[pair
 * capacity]: 1 + the step in which last step's pair q was found again with points). */
TB_STRUCT(tb_gpu_events_push) {
    TB_UVEC4 args;
    TB_UVEC4 address;
};
#define TB_EVENTS_BEGIN         TB_U(0)   /* per pair of this step: those new with points */
#define TB_EVENTS_END           TB_U(1)   /* per pair of last step: those with points, unmatched */
#define TB_EVENTS_END_GROUPS    256       /* workgroups of the end pass (a grid-stride loop) */

/* Push constants of the broadphases' own kernels (src/broadphase): their buffers are passed
 * as device addresses, so a broadphase needs no binding of the world's set. */
TB_STRUCT(tb_gpu_broadphase_push) {
    TB_UVEC4 args;            /* x mode (TB_BROADPHASE_COUNT / _WRITE for the pair search; other
                                 kernels their own), y z w kernel-defined */
    TB_UVEC4 address[4];      /* eight device addresses as (low, high) pairs in xy and zw,
                                 kernel-defined */
};
/* Modes of a pair search (args.x): count each finder's pairs, or write them. */
#define TB_BROADPHASE_COUNT     TB_U(0)
#define TB_BROADPHASE_WRITE     TB_U(1)

/* ---- Linear BVH (src/gpu/lbvh.c, glsl/common/lbvh.glsl; the lbvh broadphase) ----------
 * Karras 2012 over items sorted by key: leaf k is the k-th sorted item, internal node i
 * (0 is the root) splits at the highest bit where its range's keys differ (equal keys by
 * index). Nodes live in one array of 2 * capacity: internal nodes from 0, leaves from
 * capacity. A node reference is an internal node's index, TB_LBVH_LEAF | k for leaf k, or
 * TB_LBVH_END. Each node keeps its escape: the node that follows its subtree in depth-first
 * order, so a query walks the tree without a stack (hit: go to the left child, miss or
 * leaf: take the escape); started at a leaf's escape, it visits only the leaves after it. */
#define TB_LBVH_LEAF            TB_U(0x80000000)
#define TB_LBVH_END             TB_U(0xffffffff)
#define TB_LBVH_KEY_BITS        30   /* Morton codes: 10 bits per axis */
#define TB_LBVH_KEY_END         (TB_U(1) << TB_LBVH_KEY_BITS) /* keys from here on are no
                                        leaves; they sort after every leaf */
TB_STRUCT(tb_gpu_lbvh_node) {
    TB_UVEC4 lo;              /* xyz box minimum (float bits); w internal: its left child (the
                                 right one is links' start of left + 1), leaf: its item */
    TB_UVEC4 hi;              /* xyz box maximum (float bits); w its escape (while building an
                                 internal node: the last leaf of its range) */
};
/* The links array: sections of `capacity` uints, then the leaf count (one uint). */
#define TB_LBVH_LINK_PARENT     0    /* parent of internal node i (the root's: TB_LBVH_END) */
#define TB_LBVH_LINK_LEAF_PARENT 1   /* parent of leaf k */
#define TB_LBVH_LINK_ARRIVALS   2    /* children of internal node i the refit has finished */
#define TB_LBVH_LINK_START      3    /* the node whose range starts at leaf k > 0 (a right child) */
#define TB_LBVH_LINK_SECTIONS   4
/* Push constants of the build kernels (broadphase/lbvh_build_*). */
TB_STRUCT(tb_gpu_lbvh_push) {
    TB_UVEC4 args;            /* x capacity (items the arrays hold), y z w unused */
    TB_UVEC4 keys;            /* xy sorted keys (uint), zw their items (uint) */
    TB_UVEC4 counts;          /* xy address of the count of sorted keys, zw address of a uint
                                 that, when nonzero, says do nothing (0: none) */
    TB_UVEC4 tree;            /* xy nodes, zw links */
    TB_UVEC4 boxes;           /* per item, xy minimum and zw maximum corners (vec4, xyz used) */
};
/* The lbvh broadphase's keys beyond the tree: large static bodies (tested by every dynamic
 * body from the run of these keys), then dead slots. Sorted with 31 key bits. */
#define TB_LBVH_KEY_LARGE       TB_LBVH_KEY_END
#define TB_LBVH_KEY_DEAD        (TB_LBVH_KEY_END + TB_U(1))
#define TB_LBVH_SORT_BITS       31
/* Static bodies whose side is at least this are unbounded (planes): out of the scene bounds. */
#define TB_LBVH_UNBOUNDED_SIDE  1.0e15
/* Centre bounds of the lbvh broadphase's tree bodies: xyz of `hi` the largest centre
 * coordinates, of `lo` the smallest, as order-preserving uints (lo inverted) so both grow
 * by atomicMax from 0, which means none. */
TB_STRUCT(tb_gpu_lbvh_bounds) {
    TB_UVEC4 hi;              /* xyz ordered bits of the largest centre, w unused */
    TB_UVEC4 lo;              /* xyz inverted ordered bits of the smallest centre, w unused */
};
/* Partners the lbvh broadphase's counting walk keeps per entry (uint[CACHED * capacity],
 * partner k of entry s at k * capacity + s): the writing pass copies an entry that found
 * no more than this from there instead of walking the tree again. */
#define TB_LBVH_CACHED_PAIRS    16
/* Most workgroups of broadphase/lbvh_bounds (a grid-stride loop covers the rest). */
#define TB_LBVH_BOUNDS_GROUPS   1024

/* Incremental 3-axis sort and sweep (src/broadphase/isap.c, glsl/broadphase/isap*): what one
 * step leaves for the next, in the half of its parity (the next step reads it, writes the
 * other half, so a step run again reads the same). */
TB_STRUCT(tb_gpu_isap_header) {
    TB_UVEC4 set;             /* x 1 once the half is written, y params.counts.w, z body slots,
                                 w contact margin (float bits) of that step */
    TB_VEC4 large;            /* x side beyond which a static body is "large", y z w unused */
};
/* Counts of one step (written anew each step) and the two halves' headers. */
TB_STRUCT(tb_gpu_isap_control) {
    TB_UVEC4 sort;            /* x endpoints sorted per axis (2 * slots), y first large and
                                 z first dead entry of axis 0's order, w 1 when a body became
                                 large or stopped being large */
    TB_UVEC4 moved;           /* xy sum of how far the endpoints moved in the orders (low, high
                                 word), z w unused */
    TB_UVEC4 search;          /* isap_decide's choice: x 1 when this step searches incrementally
                                 (the LBVH, the search from scratch, then skips), y the body
                                 slots the LBVH sorts (0 when incremental), z w unused */
    TB_UVEC4 stats;           /* x pair searches run incrementally, y from scratch */
    tb_gpu_isap_header header[2];
};
/* Push constant args.y of its kernels: the body capacity (stride of the per-axis arrays).
 * address[0] orders of halves 0 and 1, [1] positions, [2] boxes, [3] xy keys (then the sorted
 * endpoints), zw the control. */
#define TB_ISAP_KEY_LARGE       TB_U(0xfffffffe) /* sort key of a large static's endpoints */
#define TB_ISAP_KEY_DEAD        TB_U(0xffffffff) /* sort key of a dead slot's endpoints */

/* 1-axis sort and sweep (src/broadphase/sap.c, glsl/broadphase/sap*). Every kernel takes
 * the same tb_gpu_broadphase_push; its device addresses, by index (address[i / 2], xy for
 * even i, zw for odd): */
#define TB_SAP_KEYS             0 /* uint[cap]: sort key (TB_SAP_KEY_* or the ordered minimum) */
#define TB_SAP_ORDER            1 /* uint[cap]: body slot, sorted with the keys */
#define TB_SAP_BOX_MIN          2 /* uvec4[cap]: minimum corner (float bits) in sorted order, the
                                     sweep axis in x (axes turned cyclically), w the slot */
#define TB_SAP_BOX_MAX          3 /* uvec4[cap]: maximum corner, the same way, w TB_SAP_BOX_* */
#define TB_SAP_PARTIALS         4 /* tb_gpu_sap_partial[workgroups of sap_gather] */
#define TB_SAP_HEADER           5 /* tb_gpu_sap_header */
#define TB_SAP_ADDRESSES        6
/* Sort keys of the slots that stay out of the sweep, after every real key (the ordered
 * bits of a float that is not a NaN are at most 0xff800000): large bodies, then dead. */
#define TB_SAP_KEY_LARGE        TB_U(0xfffffffe)
#define TB_SAP_KEY_DEAD         TB_U(0xffffffff)
/* Flags of a sorted box (box_max.w bits). */
#define TB_SAP_BOX_DYNAMIC      TB_U(1)  /* the body is dynamic */
#define TB_SAP_BOX_OUT          TB_U(2)  /* dead or large: not swept, never a candidate */
#define TB_SAP_BOX_SPLIT        TB_U(4)  /* a compound: its pairs split by child */
/* A static body whose largest side exceeds this many times the largest dynamic side (and
 * the contact margin) is large: every dynamic body tests it instead of the sweep. */
#define TB_SAP_LARGE_FACTOR     4.0

/* The spread of the swept boxes' centres in one workgroup of sap_gather: count, mean and
 * sum of squared deviations per axis (glsl/broadphase/sap_axis.glsl folds them). */
TB_STRUCT(tb_gpu_sap_partial) {
    TB_VEC4 mean;             /* xyz mean centre, w bodies counted */
    TB_VEC4 m2;               /* xyz sum of squared deviations from the mean, w unused */
};

TB_STRUCT(tb_gpu_sap_header) {
    TB_UVEC4 state;           /* x sweep axis (0, 1, 2), chosen by the step before (0 at
                                 first); y sorted position of the first large body
                                 (= bodies swept), z of the first dead slot (the large
                                 bodies are those between); w unused */
};

/* Parallel primitives (glsl/prims, src/gpu/prims.c). Operands are device addresses passed
 * as push constants, each as a (low, high) uint pair so no shader needs int64; element
 * counts are read on the GPU from the uint at a `count` address and clamped to the largest
 * count the scratch memory was sized for. A tile is the run of elements one workgroup
 * handles; the host sizes scratch and dispatches in tiles. */
#define TB_PRIMS_SCAN_TILE      4096 /* elements per workgroup of scan and compaction */
#define TB_PRIMS_SORT_TILE      2048 /* elements per tile of the radix sort */
#define TB_PRIMS_SORT_MAX_BLOCKS 1024 /* most workgroups of a sort pass: beyond it, each takes
                                        a block of several tiles (fewer digit counts) */
#define TB_PRIMS_RADIX_BITS     8    /* key bits sorted per pass */
#define TB_PRIMS_RADIX          256  /* digits per pass: 1 << TB_PRIMS_RADIX_BITS */
#define TB_PRIMS_SCAN_MODE_SUM  TB_U(0) /* scan_reduce sums the values */
#define TB_PRIMS_SCAN_MODE_FLAGS TB_U(1) /* scan_reduce counts the nonzero flags */

/* prims/fill */
TB_STRUCT(tb_gpu_fill_push) {
    TB_UVEC4 dst;             /* xy address of element 0, zw address of the count (0: args.x) */
    TB_UVEC4 args;            /* x count when zw is 0, else the largest count; y value; z w unused */
};

/* prims/indirect_args: one VkDispatchIndirectCommand covering a count of threads. */
TB_STRUCT(tb_gpu_indirect_push) {
    TB_UVEC4 ptrs;            /* xy address of the count, zw address of the command (3 uints) */
    TB_UVEC4 args;            /* x threads per group, y most groups in x (device limit),
                                 z largest count (the count is clamped to it), w unused */
};

/* prims/scan_reduce, scan_spine, scan_down, compact_scatter */
TB_STRUCT(tb_gpu_scan_push) {
    TB_UVEC4 data;            /* xy input (values or flags), zw output (sums or indices) */
    TB_UVEC4 aux;             /* xy sum of each tile (scratch), zw where the total goes (0: nowhere) */
    TB_UVEC4 count;           /* xy address of the count, z largest count, w TB_PRIMS_SCAN_MODE_* */
};

/* prims/sort_args, sort_histogram, sort_spine, sort_scatter, copy */
TB_STRUCT(tb_gpu_sort_push) {
    TB_UVEC4 keys;            /* xy keys read, zw keys written */
    TB_UVEC4 values;          /* xy values read, zw values written */
    TB_UVEC4 spine;           /* xy count of each digit in each block of tiles, digit-major
                                 ([digit * blocks + block]; scanned in place by sort_spine),
                                 zw count of each digit in all blocks */
    TB_UVEC4 count;           /* xy address of the count, z largest count,
                                 w first key bit of the digit | digit bits << 8 */
    TB_UVEC4 plan;            /* xy address of the plan sort_args writes: uint [0..2] the
                                 dispatch of the blocks, [4..6] that of sort_spine, [8] tiles
                                 per block, [9] blocks; z subgroups per workgroup of
                                 sort_spine, w most blocks */
};

/* Contact manifold of one pair: up to four points sharing a normal. */
TB_STRUCT(tb_gpu_manifold) {
    TB_VEC4 normal;           /* xyz unit normal pointing from body a to body b, w friction */
    TB_UVEC4 info;            /* x point count, y body a, z body b, w restitution (float bits) */
    TB_VEC4 point[TB_MAX_MANIFOLD_POINTS];    /* xyz world point midway between the surfaces,
                                                 w separation (m, negative when penetrating) */
    TB_VEC4 impulse[TB_MAX_MANIFOLD_POINTS];  /* accumulated over a substep: x normal, y tangent
                                                 1, z tangent 2; w the normal impulse of the
                                                 whole step (the sum over its substeps); N s
                                                 (the block solver's sweeps keep the point's
                                                 stiffness in w until the last) */
    TB_UVEC4 feature;         /* feature key of each point: which features of a and b touch */
    TB_UVEC4 axis;            /* the separating-axis test's choice, cached for the next step:
                                 x the axis (its kind and features, narrowphase-defined; 0 none),
                                 y its separation (float bits; for a touching hull pair how far
                                 the two moved since it was chosen), z while its points are
                                 left to narrowphase/hull_points the axis of largest
                                 separation (never 0), w the block solver's stiffness of
                                 the pair (float bits; see glsl/block/). A pair with a
                                 capsule, cylinder or cone keeps in y the supports its GJK
                                 took (0: none), and in x, from narrowphase/round_cull to
                                 round_points, last step's manifold of the pair */
    TB_VEC4 slip[TB_MAX_MANIFOLD_POINTS / 2]; /* the block solver's static friction: how far
                                 point k's two surfaces have moved apart along the tangents
                                 since it began to stick (m), in slip[k / 2].xy (k even) or .zw */
    /* The manifold as it was measured, so that a later step whose pair has hardly moved
     * since measures these points again instead of running the narrowphase
     * (glsl/narrowphase/reuse.glsl). Point k on a's surface is anchor_a[k].xyz (in a's
     * frame) moved anchor_a[k].w along the normal, on b's anchor_b[k] against it: */
    TB_VEC4 anchor_a[TB_MAX_MANIFOLD_POINTS];
    TB_VEC4 anchor_b[TB_MAX_MANIFOLD_POINTS];
    TB_VEC4 measured_normal;  /* xyz the normal in the frame of the body w names (reuse.glsl;
                                 w 0: the manifold is not to be measured again) */
    TB_VEC4 measured_turn;    /* b's rotation in a's frame (unit quaternion) */
    TB_VEC4 measured_offset;  /* xyz b's centre in a's frame; w the two shapes' key (bits) */
};

/* Solver data of one contact point, prepared once per step (solver/prepare). Masses are
 * effective masses 1 / (J M^-1 J^T) along the normal and the two tangents. The lever arms are
 * the step's: substeps move the bodies, and the solve tracks the separation as the adjusted
 * separation plus how far the arms' ends have moved apart along the normal. */
TB_STRUCT(tb_gpu_constraint_point) {
    TB_VEC4 ra;               /* xyz point relative to a's centre, w normal effective mass */
    TB_VEC4 rb;               /* xyz point relative to b's centre, w adjusted separation: the
                                 separation minus dot(rb - ra, normal) (m) */
    TB_VEC4 mass;             /* x tangent 1 mass, y tangent 2 mass, z relative normal velocity
                                 before the step (m/s), w the most negative one the solve has
                                 seen (restitution answers the faster approach); the block
                                 solver keeps the bounce impulse in w (glsl/block/bounce.comp) */
};

/* Indexed like the pairs of this step's half (constraints[p] for pairs[half base + p]). */
TB_STRUCT(tb_gpu_constraint) {
    TB_VEC4 tangent1;         /* xyz first friction direction, w friction coefficient */
    TB_VEC4 tangent2;         /* xyz second friction direction, w restitution */
    tb_gpu_constraint_point p[TB_MAX_MANIFOLD_POINTS];
};

/* A node of a triangle mesh's bounding volume hierarchy (src/geom/bvh.h), in depth-first
 * order: an inner node's first child follows it, and its skip index is the first node after
 * its subtree, so a walk needs no stack. The box is quantized to 16 bits per axis over the
 * mesh's box (q = fraction * 65535), rounded outward. */
#define TB_BVH_LEAF          TB_U(0x80000000) /* in tb_gpu_bvh_node.q.w: a leaf */
#define TB_BVH_MAX_TRIANGLES TB_U(16777216)   /* triangles in one mesh */
TB_STRUCT(tb_gpu_bvh_node) {
    TB_UVEC4 q;               /* x min.x | min.y << 16, y min.z | max.x << 16,
                                 z max.y | max.z << 16, w a leaf: TB_BVH_LEAF | its triangle;
                                 an inner node: its skip index */
};

/* midphase/bvh_query: each query box walks a mesh's BVH (the walk the mesh midphase does). */
TB_STRUCT(tb_gpu_bvh_query_push) {
    TB_UVEC4 arrays;          /* xy address of the nodes, zw of the queries (two vec4 each:
                                 low corner, high corner) */
    TB_UVEC4 results;         /* xy address of the results (per query: the count, the nodes
                                 looked at, then up to z triangles), z most kept per query,
                                 w query count */
    TB_VEC4 mesh_lo;          /* xyz the mesh's box, low corner; w the node count (uint bits) */
    TB_VEC4 mesh_hi;          /* xyz its high corner */
    TB_VEC4 scale;            /* xyz quantization steps per metre (65535 / extent, 0 if flat) */
};

/* A triangle mesh's GPU image (src/geom/mesh.h packs it): one buffer per mesh shape, whose
 * device address is the shape's tb_gpu_shape.hull.xy, in uvec4 units: the header below, the
 * BVH's nodes (tb_gpu_bvh_node), the triangles, the vertices. A triangle is three vertex
 * indices (x y z, counter-clockwise seen from its front: the side it collides on) and its
 * flags (w): which of its edges are active (edge k runs from vertex k to vertex k + 1 mod 3)
 * and whether it is degenerate (no contacts). An edge is active where a body may touch it
 * with a normal other than the triangle's: on the mesh's border, where more than two
 * triangles or two of opposite windings meet, and on a convex crease sharper than
 * TB_MESH_FLAT_COSINE; an edge between two triangles that are coplanar or fold concavely is
 * inactive, so a body sliding across it meets the faces only (no bump). A vertex is
 * active when one of its triangle's edges at it is. */
#define TB_MESH_EDGE_ACTIVE_0     TB_U(1)
#define TB_MESH_EDGE_ACTIVE_1     TB_U(2)
#define TB_MESH_EDGE_ACTIVE_2     TB_U(4)
#define TB_MESH_DEGENERATE        TB_U(8)
#define TB_MESH_FLAT_COSINE       0.9998   /* cos of about 1.15 degrees */
TB_STRUCT(tb_gpu_mesh_header) {
    TB_VEC4 lo;               /* xyz the mesh's box, low corner (the quantization's origin);
                                 w the node count (uint bits) */
    TB_VEC4 scale;            /* xyz quantization steps per metre (65535 / extent, 0 if flat);
                                 w the triangle count (uint bits) */
    TB_VEC4 hi;               /* xyz the box's high corner; w the vertex count (uint bits) */
    TB_UVEC4 sections;        /* where each part starts, in uvec4 from the image's start:
                                 x nodes, y triangles, z vertices (vec4, w 0); w unused */
};

/* A heightfield's GPU image (src/geom/heightfield.h packs it), reached like a mesh's (its
 * shape's tb_gpu_shape.hull.xy), in uvec4 units: the header, the heights (four to a uvec4,
 * row by row along x: sample (i, k) at k * counts.x + i), the cells' flags (four to a uvec4,
 * cell (i, k) at k * (counts.x - 1) + i). Sample (i, k) lies at x = lo.x + i * cell_x,
 * z = lo.z + k * cell_z. Cell (i, k) is two triangles of the samples a = (i, k),
 * b = (i + 1, k), c = (i, k + 1), d = (i + 1, k + 1): triangle 2n = (a, c, b) and 2n + 1 =
 * (b, c, d) for n = k * (counts.x - 1) + i, facing +y; a cell's flags hold triangle 2n's
 * TB_MESH_* bits in bits 0-3 and 2n + 1's in bits 4-7 (a hole's are TB_MESH_DEGENERATE). */
TB_STRUCT(tb_gpu_heightfield_header) {
    TB_VEC4 lo;               /* x z the first sample's place, y the lowest height; w cell_x */
    TB_VEC4 hi;               /* x z the last sample's place, y the highest height; w cell_z */
    TB_UVEC4 counts;          /* x samples along x, y along z, z first height, w first cell's
                                 flags (uvec4 from the image's start) */
};

/* A compound's GPU image (src/geom/compound.h packs it), reached like a mesh's (its shape's
 * tb_gpu_shape.hull.xy): a uvec4 header (x the child count) and then one
 * tb_gpu_compound_child per child. Children are convex shapes of the shape table placed in
 * the compound's body frame (its centre-of-mass principal frame). */
#define TB_COMPOUND_MAX_CHILDREN  64
TB_STRUCT(tb_gpu_compound_child) {
    TB_VEC4 position;         /* xyz the child's origin in the body frame; w its shape index
                                 (uint bits) */
    TB_VEC4 rotation;         /* the child's frame in the body frame, quaternion xyzw */
    TB_VEC4 box_center;       /* xyz the child's box in the body frame: centre */
    TB_VEC4 box_half;         /* xyz half extents */
};

/* Which part of its bodies a pair is (pairs[].w, written where the pair is found or split):
 * a pair with a mesh body holds its triangle + 1 in the low TB_PAIR_TRIANGLE_BITS bits and,
 * when the other body is a compound, the child's index above them; a pair without a mesh
 * body holds body a's child index in the low 16 bits and body b's in the high 16 (0 for a
 * body that is not a compound). */
#define TB_PAIR_TRIANGLE_BITS     25
#define TB_PAIR_TRIANGLE_MASK     ((TB_U(1) << TB_PAIR_TRIANGLE_BITS) - TB_U(1))
/* The broadphase's record of a pair with a mesh or compound body, before the midphase split
 * (glsl/midphase/split.glsl) replaces it by its triangle or child pairs; after the split,
 * a compound pair none of whose parts touch, kept for isap (its manifold is empty). */
#define TB_PAIR_UNSPLIT           TB_U(0xffffffff)

/* query/distance (tb_world_query_distances): the distance between two convex shapes placed
 * by poses, GJK on their cores and, where the cores overlap, EPA or MPR as the query chose
 * (glsl/narrowphase/gjk.glsl, epa.glsl, mpr.glsl). One thread per query.
 *
 * The shape-index words (position_a.w, position_b.w, uint bits) hold the shape's slot in
 * their low TB_DISTANCE_SHAPE_BITS bits (the host refuses a slot that does not fit). Above
 * them position_a.w holds the penetration method, TB_DISTANCE_METHOD_EPA or _MPR (the host
 * resolves TB_PENETRATION_DEFAULT); position_b.w holds 0 there. With the method at most 1
 * the word is a small float's bits, never a NaN's. */
#define TB_DISTANCE_SHAPE_BITS    24
#define TB_DISTANCE_SHAPE_MASK    ((TB_U(1) << TB_DISTANCE_SHAPE_BITS) - TB_U(1))
#define TB_DISTANCE_METHOD_EPA    TB_U(0)
#define TB_DISTANCE_METHOD_MPR    TB_U(1)
TB_STRUCT(tb_gpu_distance_query) {
    TB_VEC4 position_a;       /* xyz shape a's origin, w its shape index and the method
                                 (uint bits, above) */
    TB_VEC4 rotation_a;       /* unit quaternion xyzw */
    TB_VEC4 position_b;       /* as for a */
    TB_VEC4 rotation_b;
};
TB_STRUCT(tb_gpu_distance_result) {
    TB_VEC4 point_a;          /* xyz the closest (or deepest) point on a, w the distance
                                 (negative: the depth of overlap) */
    TB_VEC4 point_b;          /* xyz on b, w the status (uint bits: TB_DISTANCE_* of tumble.h) */
    TB_VEC4 normal;           /* xyz unit, from a to b; w the GJK iterations (uint bits) */
};
TB_STRUCT(tb_gpu_distance_push) {
    TB_UVEC4 arrays;          /* xy address of the queries, zw of the results */
    TB_UVEC4 range;           /* x the first query of this dispatch, y the query count */
};

/* A shape as the GPU sees it. */
TB_STRUCT(tb_gpu_shape) {
    TB_VEC4 aabb_center;    /* xyz centre of the local AABB, body frame */
    TB_VEC4 aabb_half;      /* xyz half extents of the local AABB */
    TB_VEC4 params;         /* sphere: x radius; box: xyz half extents; plane: xyz normal, w offset;
                               capsule, cylinder, cone: x radius, y half height (along the
                               body's y axis; a cone's base at y = -y/2, apex at 3y/2) */
    TB_UVEC4 info;          /* x TB_GPU_SHAPE_*; hulls (boxes too): y vertex count, z face
                               count, w edge count; compounds: y child count */
    TB_VEC4 material;       /* x friction coefficient, y restitution, z w reserved */
    TB_UVEC4 hull;          /* hulls (boxes too): x first vertex, y first face plane (indices into
                               hull_vectors), z first edge, w face base (indices into
                               hull_topology); the geometry is in the body frame, which for a
                               hull is its centre-of-mass principal frame; meshes,
                               heightfields and compounds: xy their image's device address */
};

#endif
