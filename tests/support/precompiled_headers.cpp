// Owns the test suite's precompiled header (tests/CMakeLists.txt, sandtin_test_pch): CMake builds
// a precompiled header with the flags of a target, and this translation unit gives it a target
// of its own that every test executable reuses. It defines nothing.
