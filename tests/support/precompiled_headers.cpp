// The source of eco_test_headers (tests/CMakeLists.txt): empty, its headers are what is compiled.
