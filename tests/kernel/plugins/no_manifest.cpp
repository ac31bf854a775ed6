// A shared library that is not a rollsense plugin (no manifest symbol).
extern "C" __attribute__((visibility("default"))) int some_other_function() { return 7; }
