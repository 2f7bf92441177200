#pragma once
// Where the programs find the files of the repository's data/ folder at run time.
#include <string>

namespace cupola {

// The path of data/<relative>, from the first of these places that applies:
//   1. $CUPOLA_DATA_DIR/<relative> when that variable is set (and only there);
//   2. <executable dir>/CUPOLA_BIN_TO_DATA/data/<relative>, the installed layout
//      (/usr/bin/cupola-slave -> /usr/share/cupola/data/..., cmake/Packaging.cmake), when the file is there;
//   3. CUPOLA_SOURCE_DIR/data/<relative>, the source tree, for programs run from the build tree.
// Throws std::runtime_error naming the file and every place looked in when none has it.
std::string data_file(const std::string& relative);

}  // namespace cupola
