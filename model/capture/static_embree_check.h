// Before a capture runs the application: a program that defines Embree's
// functions itself (a statically linked Embree, or stand-ins of its own) calls
// them directly, past any preloaded library, so the shim would see nothing.
// Such a program is refused before it runs, with the reason. The check reads
// the ELF symbol tables of the file the command names (looked up on PATH as
// execvp does); a stripped program (no symbol table) that imports no
// rtcIntersect1 is refused when its bytes hold Embree's code, told by the
// type name of Embree's device class that every build carries for its
// exceptions (kEmbreeCodeMarker). A script, a program that loads Embree as a
// shared library and a file that cannot be read pass, and the run itself
// decides (a trace, or the merge's "no process loaded a shared libembree3").
#pragma once
#include <string>
#include <vector>

namespace vbsim::capture {

/// The mangled type name of embree::Device, in the read-only data of every
/// program or library that holds Embree 3's code, stripped or not.
constexpr const char* kEmbreeCodeMarker = "N6embree6DeviceE";

/// The reason `command` cannot be captured because its executable defines
/// rtcIntersect1 itself, or holds Embree's code stripped of its symbols;
/// empty when the check finds neither.
std::string embree_defined_by_program(const std::vector<std::string>& command);

/// The file execvp would run for `name`: `name` itself when it holds a '/',
/// else the first executable file of that name on $PATH; empty when none.
std::string resolve_on_path(const std::string& name);

/// Whether the ELF file at `path` (64-bit, little-endian) defines the function
/// `symbol` in its symbol table or its dynamic symbol table; false for any
/// other file or one that cannot be read.
bool elf_defines_function(const std::string& path, const std::string& symbol);

/// Whether it names `symbol` as undefined (imported from a shared library).
bool elf_imports(const std::string& path, const std::string& symbol);

/// Whether the file at `path` holds `bytes` anywhere; false when it cannot be read.
bool file_contains(const std::string& path, const std::string& bytes);

}  // namespace vbsim::capture
