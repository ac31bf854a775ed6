// The library missing_dependency.cpp links against; the loader is never told where it is.
int rollsense_test_dependency_value() { return 1; }
