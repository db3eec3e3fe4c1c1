#pragma once
// The page's own files (src/view/page/), compiled into the program so that `eco view` needs no
// install path: generated at build time by cmake/embed_page.cmake.

#include <span>
#include <string_view>

namespace eco::view {

struct PageFile {
  std::string_view path;          ///< as requested: "/index.html"
  std::string_view content_type;
  std::string_view body;
};

[[nodiscard]] std::span<const PageFile> page_files();

}  // namespace eco::view
