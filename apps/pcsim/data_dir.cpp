#include "data_dir.hpp"

#include <system_error>

namespace pcsim {

namespace fs = std::filesystem;

fs::path data_dir_looked_at() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) return {};
  return (self.parent_path() / PCSIM_DATA_RELATIVE).lexically_normal();
}

fs::path data_dir() {
  const fs::path dir = data_dir_looked_at();
  std::error_code error;
  if (dir.empty() || !fs::is_directory(dir / "validation" / "paper", error)) return {};
  return dir;
}

}  // namespace pcsim
