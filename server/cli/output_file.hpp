#pragma once
// --out FILE: the answer written to a temporary beside FILE and renamed over it, so that FILE is either the whole
// answer or untouched. An existing FILE keeps its permission bits; one that is not a regular file is refused
// (a FIFO or a symbolic link unless `through`: then a FIFO is written into, and a link's target is replaced as
// FILE would be). The temporary is removed on an error and on every signal that ends the process and can be caught.
#include <string>

namespace lienewton::cli {

void write_output_file(const std::string& path, const std::string& bytes, bool through);

}  // namespace lienewton::cli
