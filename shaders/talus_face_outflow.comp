#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 1 of a Jacobi iteration under the face rule (SlopeRule::Face): the outflow of every
// active vertex, from the old heights, transcribing engine/physics/face_kernel.hpp (face_shed
// and face_row_scale) in float. Per slot k of i's row, across[k] (m) is the length of the edge
// between target[k] and the next slot's target when the three make a face, else 0 (the
// mirror's EdgeBuffer::Across, AdjacencyGraph::across()). The gather is the edge rule's.
#include "talus_outflow_common.glsl"

layout(std430, binding = 18) readonly buffer Across { float across[]; };

// One face's excess (m, at the settle margin) and its receivers' shares (face_kernel.hpp).
struct FaceShed {
    float excess;
    float to_j;
    float to_l;
};

// j (or, with j_refuses false, l) takes nothing: the other corner takes its share.
FaceShed refuse(FaceShed f, bool j_refuses) {
    if (j_refuses) {
        f.to_l += f.to_j;
        f.to_j = 0.0;
    } else {
        f.to_j += f.to_l;
        f.to_l = 0.0;
    }
    return f;
}

// The face (i, j, l): |ij| = a, |il| = b, |jl| = c (m), heights hi, hj, hl (m).
FaceShed face_shed(float a, float b, float c, float hi, float hj, float hl, float tan_a,
                   float noise_floor) {
    FaceShed f = FaceShed(0.0, 0.0, 0.0);
    float dj = (a * a + c * c - b * b) / (2.0 * c);  // foot of the altitude, from j
    float alt2 = a * a - dj * dj;
    if (!(alt2 > 1e-14 * a * a)) return f;  // i on the line jl: no plane to judge
    float alt = sqrt(alt2);
    float s = dj / c;
    float gt = (hl - hj) / c;
    if (abs(gt) < tan_a) {
        float trigger = hi - (hj + s * (hl - hj) + alt * sqrt(tan_a * tan_a - gt * gt));
        if (!(trigger > pc.rest_tolerance * alt * tan_a) || !(trigger > noise_floor)) return f;
        float margin_tan = (1.0 - pc.settle_margin) * tan_a;
        float level_tan = abs(gt) < margin_tan ? margin_tan : tan_a;
        float w = sqrt(level_tan * level_tan - gt * gt);
        f.excess = hi - (hj + s * (hl - hj) + alt * w);
        // Where the steepest-descent line of the levelled plane meets the line jl.
        float t = clamp(s - gt * alt / (w * c), 0.0, 1.0);
        f.to_j = 1.0 - t;
        f.to_l = t;
    } else {
        // The opposite edge is steeper than repose: the edge rule towards the lower corner.
        bool towards_j = hj <= hl;
        float r = towards_j ? a : b;
        float e = hi - (towards_j ? hj : hl) - r * tan_a;
        if (!(e > pc.rest_tolerance * r * tan_a) || !(e > noise_floor)) return f;
        f.excess = e + pc.settle_margin * r * tan_a;
        f.to_j = towards_j ? 1.0 : 0.0;
        f.to_l = towards_j ? 0.0 : 1.0;
    }
    // Sand never climbs: a corner above i takes no share.
    if (hj >= hi) f = refuse(f, true);
    if (hl >= hi) f = refuse(f, false);
    if (!(f.to_j + f.to_l > 0.0)) f.excess = 0.0;
    return f;
}

void main() {
    uint idx = thread_index();
    if (idx >= ctl[C_ACTIVE]) return;
    uint i = lists[ctl[C_PARITY] * pc.capacity + idx];
    uint begin = row_offset[i];
    uint degree = row_degree[i];
    uint end = begin + degree;
    vs[i].source = pc.iter;
    float sent = 0.0;
    if (degree > 0u) {
        float hi = height[i];
        float tan_a = tan_alpha[i];
        float inv_ai = 1.0 / area[i];
        float degenerate = kDegenerateAreaRatio * area[i];
        // As in talus_outflow.comp: 4 float ulps of the height are rounding noise.
        float noise_floor = 4.0 * kFloatEpsilon * abs(hi);
        // Two faces send to each neighbour: the row's q is accumulated in place (only this
        // invocation writes i's row), then scaled.
        for (uint k = begin; k < end; ++k) q[k] = 0.0;
        float largest = 0.0;
        float levelling = 0.0;
        for (uint k = begin; k < end; ++k) {
            float c = across[k];
            if (!(c > 0.0)) continue;
            uint kn = k + 1u == end ? begin : k + 1u;
            uint j = target[k];
            uint l = target[kn];
            float hj = height[j];
            float hl = height[l];
            FaceShed f = face_shed(edge_length[k], edge_length[kn], c, hi, hj, hl, tan_a,
                                   noise_floor);
            if (!(f.excess > 0.0)) continue;
            if (edge_length[k] > pc.r_limit || edge_length[kn] > pc.r_limit) {
                request_split(i);
                continue;
            }
            if (longest[j] > pc.r_limit || longest[l] > pc.r_limit) {
                request_split(longest[j] > pc.r_limit ? j : l);
                continue;
            }
            // A degenerate receiver passes its share to the other, or the face sheds nothing.
            if (area[j] < degenerate) f = refuse(f, true);
            if (area[l] < degenerate) f = refuse(f, false);
            if (!(f.to_j + f.to_l > 0.0)) continue;
            float denominator = inv_ai + (f.to_j > 0.0 ? f.to_j * f.to_j / area[j] : 0.0) +
                                (f.to_l > 0.0 ? f.to_l * f.to_l / area[l] : 0.0);
            // Each receiver takes at most what would level it with i alone.
            float volume = f.excess / denominator;
            float to_j = f.to_j > 0.0
                             ? min(f.to_j * volume, max(0.0, hi - hj) / (inv_ai + 1.0 / area[j]))
                             : 0.0;
            float to_l = f.to_l > 0.0
                             ? min(f.to_l * volume, max(0.0, hi - hl) / (inv_ai + 1.0 / area[l]))
                             : 0.0;
            if (!(to_j + to_l > 0.0)) continue;
            q[k] += to_j;
            q[kn] += to_l;
            levelling += to_j + to_l;
            largest = max(largest, f.excess);
        }
        float scale = largest > 0.0 ? row_scale(i, hi, largest, levelling) : 0.0;
        // A drop of i within the noise floor is rounding, not sand (face_row_scale).
        if (!(scale * levelling * inv_ai > noise_floor)) scale = 0.0;
        // Every slot of the row is written (receivers read q of every source's row).
        for (uint k = begin; k < end; ++k) {
            float v = scale > 0.0 ? q[k] * scale : 0.0;
            q[k] = v;
            sent += v;
        }
    }
    finish_outflow(i, begin, degree, sent);
}
