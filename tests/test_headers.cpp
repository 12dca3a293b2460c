// The source of substep_test_headers (tests/CMakeLists.txt): a library that exists to own the
// precompiled header every test program reuses. It has nothing of its own to compile.
