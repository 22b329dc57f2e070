#version 450
#extension GL_GOOGLE_include_directive : require
// Active-set bookkeeping after an iteration (physics/active_set.hpp, ActiveSet::age): an active
// vertex whose height did not change counts one more quiet iteration and leaves after
// quiet_limit of them; the others go to the next list.
#include "talus_common.glsl"

void main() {
    uint idx = thread_index();
    if (idx >= ctl[C_ACTIVE]) return;
    uint v = lists[ctl[C_PARITY] * pc.capacity + idx];
    if (vs[v].changed == pc.iter) {
        vs[v].quiet = 0u;
    } else {
        uint quiet = vs[v].quiet + 1u;
        vs[v].quiet = quiet;
        if (quiet >= pc.quiet_limit) {
            vs[v].in_list = 0u;
            return;
        }
    }
    append(1u - ctl[C_PARITY], C_NEXT, v);
}
