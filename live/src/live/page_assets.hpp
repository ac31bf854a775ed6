// The live view's page files (live/page/), embedded at build time by
// live/embed_page.cmake: served from memory, so the page works offline.
#pragma once

#include <string_view>
#include <vector>

namespace rollsense::live {

struct PageAsset {
    std::string_view path;          // "/index.html"
    std::string_view content_type;
    std::string_view content;
};
const std::vector<PageAsset>& page_assets();

}  // namespace rollsense::live
