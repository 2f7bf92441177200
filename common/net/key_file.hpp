#pragma once
// The cluster's shared authentication key, read from a file with a permission check.
#include <string>

#include "wire/packet.hpp"

namespace cupola {

// Reads a key file: 64 hexadecimal digits (whitespace ignored). Throws naming the file.
// A key file that every user of the machine can read (or write) lets them forge cluster packets:
// that is a warning, or with `strict` (security.strict_key_permissions) an error naming the file
// and its mode. Group access is allowed (a "cupola" group on the render nodes).
AuthKey load_key_file(const std::string& path, bool strict = false);

}  // namespace cupola
