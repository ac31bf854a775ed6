// Empty: the source file of rollsense_test_pch, the target that builds Catch's precompiled header once for every
// test executable (cmake/RollsenseTesting.cmake).
