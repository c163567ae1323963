#include "capture/static_embree_check.h"

#include <elf.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace vbsim::capture {

namespace {

template <class T>
bool read_at(std::ifstream& in, uint64_t offset, T& out) {
  in.seekg(static_cast<std::streamoff>(offset));
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&out), sizeof(T)));
}

/// Whether symbol table section `sym` (with its string table section `str`)
/// names the function `name`: defined (`defined`), or undefined (imported).
bool table_names(std::ifstream& in, const Elf64_Shdr& sym, const Elf64_Shdr& str, const std::string& name,
                 bool defined) {
  if (sym.sh_entsize != sizeof(Elf64_Sym) || str.sh_size == 0 || str.sh_size > (uint64_t{1} << 30)) return false;
  std::string strings(str.sh_size, '\0');
  in.seekg(static_cast<std::streamoff>(str.sh_offset));
  if (!in.read(strings.data(), static_cast<std::streamsize>(strings.size()))) return false;
  const uint64_t count = sym.sh_size / sizeof(Elf64_Sym);
  for (uint64_t k = 0; k < count; ++k) {
    Elf64_Sym s;
    if (!read_at(in, sym.sh_offset + k * sizeof(Elf64_Sym), s)) return false;
    if ((s.st_shndx == SHN_UNDEF) == defined || s.st_name >= strings.size()) continue;
    if (defined && ELF64_ST_TYPE(s.st_info) != STT_FUNC) continue;
    if (std::strcmp(strings.c_str() + s.st_name, name.c_str()) == 0) return true;
  }
  return false;
}

}  // namespace

std::string resolve_on_path(const std::string& name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

namespace {

/// Whether the 64-bit little-endian ELF file at `path` names `symbol` in a
/// symbol table: as a defined function, or as an undefined symbol.
bool elf_names(const std::string& path, const std::string& symbol, bool defined) {
  std::ifstream in(path, std::ios::binary);
  Elf64_Ehdr eh;
  if (!in || !read_at(in, 0, eh)) return false;
  if (std::memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0 || eh.e_ident[EI_CLASS] != ELFCLASS64 ||
      eh.e_ident[EI_DATA] != ELFDATA2LSB || eh.e_shentsize != sizeof(Elf64_Shdr) || eh.e_shnum == 0)
    return false;
  for (unsigned i = 0; i < eh.e_shnum; ++i) {
    Elf64_Shdr sh;
    if (!read_at(in, eh.e_shoff + uint64_t{i} * sizeof(Elf64_Shdr), sh)) return false;
    if (sh.sh_type != SHT_SYMTAB && sh.sh_type != SHT_DYNSYM) continue;
    Elf64_Shdr str;
    if (sh.sh_link >= eh.e_shnum || !read_at(in, eh.e_shoff + uint64_t{sh.sh_link} * sizeof(Elf64_Shdr), str))
      return false;
    if (table_names(in, sh, str, symbol, defined)) return true;
  }
  return false;
}

}  // namespace

bool elf_defines_function(const std::string& path, const std::string& symbol) { return elf_names(path, symbol, true); }

bool elf_imports(const std::string& path, const std::string& symbol) { return elf_names(path, symbol, false); }

bool file_contains(const std::string& path, const std::string& bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in || bytes.empty()) return false;
  constexpr std::size_t kChunk = 1 << 20;
  std::string window;  // the tail of the previous chunk, then this one
  std::string chunk(kChunk, '\0');
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    window.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (window.find(bytes) != std::string::npos) return true;
    window.erase(0, window.size() - std::min(window.size(), bytes.size() - 1));
  }
  return false;
}

std::string embree_defined_by_program(const std::vector<std::string>& command) {
  if (command.empty()) return "";
  const std::string program = resolve_on_path(command.front());
  if (program.empty()) return "";
  if (elf_defines_function(program, "rtcIntersect1"))
    return fmt::format(
        "{} defines Embree's functions itself (rtcIntersect1: a statically linked Embree, or its own): its calls "
        "never reach a preloaded library, so the capture shim cannot see them; link it to the shared libembree3 "
        "to capture it",
        program);
  if (!elf_imports(program, "rtcIntersect1") && file_contains(program, kEmbreeCodeMarker))
    return fmt::format(
        "{} holds Embree's code (its device class, {}) and imports no rtcIntersect1: a statically linked Embree, "
        "stripped of its symbols; its calls never reach a preloaded library, so the capture shim cannot see them; "
        "link it to the shared libembree3 to capture it",
        program, kEmbreeCodeMarker);
  return "";
}

}  // namespace vbsim::capture
