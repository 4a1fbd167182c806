#pragma once
// Where pcsim's data is (the paper's scenarios, the shipped platforms, the validation data and
// the inputs made by others): beside pcsim's own binary, at the path from the binaries' folder
// to the data folder of the install layout (PCSIM_DATA_RELATIVE, e.g. ../share/pcsim). An
// installed pcsim and one in its build tree (which mirrors that layout) find it the same way,
// wherever the prefix was moved: no absolute path is fixed when pcsim is built.

#include <filesystem>

namespace pcsim {

/// The data folder, or an empty path if there is none beside this binary.
std::filesystem::path data_dir();

/// The folder the lookup tried (for messages).
std::filesystem::path data_dir_looked_at();

}  // namespace pcsim
