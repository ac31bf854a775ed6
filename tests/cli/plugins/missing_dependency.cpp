// A plugin file that links against a library the loader cannot find (built
// into a folder off every search path, and without an RPATH to it): what a
// plugin whose vendor library is not installed looks like to `rollsense plugins`.
int rollsense_test_dependency_value();

extern "C" int rollsense_test_uses_dependency() { return rollsense_test_dependency_value(); }
