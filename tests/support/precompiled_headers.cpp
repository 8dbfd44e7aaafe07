// tests/support/precompiled_headers.cpp - the target that holds the test binaries' shared
// precompiled header (tests/CMakeLists.txt, voxspan_test_headers). Built, never run: GoogleTest's
// main is its main.
