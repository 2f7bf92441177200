#pragma once
// Precomputed float tables (RGBA, the shading code's Texture2DData) kept on disk between runs:
// the atmosphere's tables and the eclipse table. Written as zip-compressed 32-bit EXR with the
// table's format name in the header, to a temporary file renamed into place, so that processes
// starting together never read a half-written table.
#include <filesystem>
#include <string>

#include "shading/glsl_compat.hpp"

namespace cupola {

// False when the file cannot be written (the caller goes on without a cache).
bool write_table_file(const std::filesystem::path& path, const shading::Texture2DData& table,
                      const std::string& format);

// Reads a table written by write_table_file; false, with why, when the file is missing, has
// another size or format, or holds a non-finite or negative texel.
bool read_table_file(const std::filesystem::path& path, int width, int height, const std::string& format,
                     shading::Texture2DData& table, std::string& why);

// The folder for cached data of one kind ("atmosphere", "eclipse"): $CUPOLA_CACHE_DIR as given,
// else $XDG_CACHE_HOME/cupola/<kind>, else $HOME/.cache/cupola/<kind>, else ./.cupola-cache/<kind>.
std::string cache_directory(const std::string& kind);

// A short hex digest of text (BLAKE2b, 12 bytes): the key a cached table is filed under.
std::string cache_key_hex(const std::string& text);

}  // namespace cupola
