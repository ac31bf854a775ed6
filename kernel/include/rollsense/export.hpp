// Symbol visibility. Plugins are built with hidden visibility; the SDK's polymorphic types must still have one shared
// typeinfo across libraries so that exceptions thrown in a plugin are caught by type in the kernel.
#pragma once

#define ROLLSENSE_API __attribute__((visibility("default")))
