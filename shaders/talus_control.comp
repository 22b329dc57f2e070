#version 450
#extension GL_GOOGLE_include_directive : require
// One invocation of bookkeeping between the relaxation kernels (indirect arguments, list swap).
//   mode 0: after the outflow     -> receiver dispatch arguments
//   mode 1: after the gather      -> changed dispatch arguments
//   mode 2: end of the iteration  -> swap the active lists, count the work, reset counters
//   mode 3: after seeding / reset -> active dispatch arguments
//   mode 4: pack the touched list -> (done by talus_pack.comp; here: clear touched counter)
#include "talus_common.glsl"

void add64(uint lo_word, uint value) {
    uint lo = ctl[lo_word];
    uint sum = lo + value;
    ctl[lo_word] = sum;
    if (sum < lo) ctl[lo_word + 1] += 1u;
}

void main() {
    if (thread_index() != 0u) return;
    if (pc.mode == 0u) {
        ctl[C_RECEIVERS] = min(ctl[C_RECEIVERS], pc.capacity);
        set_args(C_ARGS_RECEIVERS, ctl[C_RECEIVERS]);
    } else if (pc.mode == 1u) {
        ctl[C_CHANGED] = min(ctl[C_CHANGED], pc.capacity);
        set_args(C_ARGS_CHANGED, ctl[C_CHANGED]);
        add64(C_CHANGED_TOTAL_LO, ctl[C_CHANGED]);
    } else if (pc.mode == 2u) {
        add64(C_PROCESSED_LO, ctl[C_ACTIVE]);
        if (ctl[C_ACTIVE] > 0u) add64(C_WORK_ITER_LO, 1u);
        ctl[C_ACTIVE] = min(ctl[C_NEXT], pc.capacity);
        ctl[C_NEXT] = 0u;
        ctl[C_RECEIVERS] = 0u;
        ctl[C_CHANGED] = 0u;
        ctl[C_PARITY] = 1u - ctl[C_PARITY];
        set_args(C_ARGS_ACTIVE, ctl[C_ACTIVE]);
    } else if (pc.mode == 3u) {
        ctl[C_ACTIVE] = min(ctl[C_ACTIVE], pc.capacity);
        ctl[C_CHANGED] = 0u;
        set_args(C_ARGS_ACTIVE, ctl[C_ACTIVE]);
    } else if (pc.mode == 4u) {
        // Only the touched counter: the split requests wait for take_split_requests(), which
        // runs after the read-back and clears its own counter. (Clearing it here dropped every
        // request of a batch that moved sand, so a pile with a relocation radius stopped
        // refining and rested twice as tall as the cone.)
        ctl[C_TOUCHED] = 0u;
    }
}
