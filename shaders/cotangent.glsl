// Cotangent weights of a vertex's CSR row on the TIN mirror, shared by the water's pipes and
// the moisture's spreading. The including shader declares the mirror's `position`, `target`
// and `across` buffers before including this file.
#ifndef SANDTIN_COTANGENT_GLSL
#define SANDTIN_COTANGENT_GLSL

// Half the cotangent of the angle at `apex` of the triangle (apex, p, r): one face's part of
// the dual edge length of edge pr over its length. `precise` keeps it symmetric in p and r
// (no fused products), so both ends of a pipe see one conductance.
float half_cotangent(vec2 apex, vec2 p, vec2 r) {
    precise vec2 u = p - apex;
    precise vec2 w = r - apex;
    precise float sine = abs(u.x * w.y - u.y * w.x);
    precise float cosine = u.x * w.x + u.y * w.y;
    return sine > 0.0 ? 0.5 * cosine / sine : 0.0;
}

// w / L of the edge along directed edge k of v's row [begin, end): the faces on either side
// of it are (v, target[k], target[next]) and (v, target[prev], target[k]), each present when
// `across` says the two targets make a face with v. A non-Delaunay edge (negative weight) conducts nothing.
float conductance(uint v, uint k, uint begin, uint end) {
    uint next = k + 1u == end ? begin : k + 1u;
    uint prev = k == begin ? end - 1u : k - 1u;
    vec2 pv = position[v];
    vec2 pw = position[target[k]];
    precise float c = 0.0;
    if (across[k] != 0.0) c += half_cotangent(position[target[next]], pv, pw);
    if (across[prev] != 0.0) c += half_cotangent(position[target[prev]], pv, pw);
    return max(c, 0.0);
}

#endif
