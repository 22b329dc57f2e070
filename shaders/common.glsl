// Shared by every sandtin compute shader.
#ifndef SANDTIN_COMMON_GLSL
#define SANDTIN_COMMON_GLSL

#define LOCAL_SIZE 64
layout(local_size_x = LOCAL_SIZE) in;

// Flat invocation index over a 2D grid of workgroups: large counts are dispatched as
// (65535, n) groups because maxComputeWorkGroupCount[0] may be 65535.
uint thread_index() {
    return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * LOCAL_SIZE;
}

#endif
