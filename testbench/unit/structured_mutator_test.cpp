// The fuzz targets' structure-aware mutator (testbench/fuzz/structured_mutator.h),
// seeded, on every seed of the corpora: each mutant goes through the target's
// checks (fuzz_checks.h), which accept it or refuse it with the reader's own
// error, never a crash. And the mutator does what it says: deep nesting,
// extreme numbers, lying counts and repeated keys all come out of it.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../fuzz/fuzz_checks.h"
#include "../fuzz/structured_mutator.h"
#include "io/json_document.h"

namespace fs = std::filesystem;
using vbsim::fuzz::InputFormat;

namespace {

struct Target {
  const char* name;
  const char* suffix;
  InputFormat format;
  void (*check)(const std::string&);
};

const Target kTargets[] = {
    {"text_trace", ".jsonl", InputFormat::JsonLines, vbsim::fuzz::check_text_trace},
    {"config", ".json", InputFormat::Json, vbsim::fuzz::check_config},
    {"binary_trace", ".vbt", InputFormat::BinaryTrace, vbsim::fuzz::check_binary_trace},
    {"scene_ply", ".ply", InputFormat::Ply, vbsim::fuzz::check_scene},
    {"scene_obj", ".obj", InputFormat::Obj, vbsim::fuzz::check_scene},
};

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// No byte mutations: what comes out is the structured mutator's own.
size_t keep_bytes(uint8_t*, size_t size, size_t) { return size; }

constexpr size_t kMaxSize = 65536;  // scripts/fuzz.sh's -max_len

}  // namespace

TEST_CASE("structured mutants of every seed are read or refused cleanly", "[fuzz]") {
  const fs::path corpus = fs::path(VBSIM_SOURCE_DIR) / "testbench" / "fuzz" / "corpus";
  const fs::path scratch = fs::temp_directory_path() / ("vbsim_mutants_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  int mutants = 0, changed = 0, deep = 0;
  for (const Target& t : kTargets) {
    for (const auto& e : fs::directory_iterator(corpus / t.name)) {
      const std::string seed = read_bytes(e.path());
      if (seed.size() > kMaxSize) continue;
      for (unsigned k = 0; k < 40; ++k) {
        std::vector<uint8_t> data(kMaxSize);
        std::copy(seed.begin(), seed.end(), data.begin());
        size_t size = seed.size();
        // Two mutations in a row: a lie on top of an extreme number, and so on.
        for (unsigned step = 0; step < 2; ++step)
          size = vbsim::fuzz::structured_mutate(t.format, data.data(), size, kMaxSize, 1000 * k + step, keep_bytes);
        const std::string mutant(reinterpret_cast<const char*>(data.data()), size);
        changed += mutant != seed;
        deep += vbsim::json_nesting_overflow(mutant) != std::string::npos;
        const fs::path file = scratch / (std::string("mutant") + t.suffix);
        {
          std::ofstream out(file, std::ios::binary | std::ios::trunc);
          out << mutant;
        }
        INFO(t.name << " seed " << e.path().filename().string() << " mutation " << k);
        CHECK_NOTHROW(t.check(file.string()));
        ++mutants;
      }
    }
  }
  fs::remove_all(scratch);
  CHECK(mutants >= 14 * 40);  // every committed seed of the five targets
  CHECK(changed > mutants / 2);  // most calls change the input (a quarter are left to the byte mutator)
  CHECK(deep > 0);               // nesting beyond the readers' limit was produced
}

TEST_CASE("structured mutator: a binary trace's header length is made to lie", "[fuzz]") {
  std::string vbt = "VBSIMTRB";
  const uint32_t version = 1, n = 2;
  vbt.append(reinterpret_cast<const char*>(&version), 4);
  vbt.append(reinterpret_cast<const char*>(&n), 4);
  vbt += "{}      ";
  std::vector<uint8_t> data(vbt.begin(), vbt.end());
  data.resize(4096);
  int lies = 0;
  for (unsigned seed = 0; seed < 64; ++seed) {
    std::vector<uint8_t> copy = data;
    const size_t size = vbsim::fuzz::structured_mutate(InputFormat::BinaryTrace, copy.data(), vbt.size(), copy.size(),
                                                       seed, keep_bytes);
    uint32_t stated = 0;
    std::memcpy(&stated, copy.data() + 12, 4);
    lies += size == vbt.size() && stated != n;
  }
  CHECK(lies > 10);
}

TEST_CASE("structured mutator: counts and inputs of any size are mutated without failing", "[fuzz]") {
  // A count beyond 2^64 (the mutator once threw std::out_of_range on it) and
  // 64 KiB of brackets (marking the values once took time quadratic in the input).
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\n"
                          "end_header\n1\n";
  const std::string brackets = std::string(32000, '[') + std::string(32000, ']');
  for (const auto& [format, text] : {std::pair<InputFormat, std::string>{InputFormat::Ply, ply},
                                     {InputFormat::Json, brackets}, {InputFormat::JsonLines, brackets}}) {
    for (unsigned seed = 0; seed < 32; ++seed) {
      std::vector<uint8_t> data(kMaxSize);
      std::copy(text.begin(), text.end(), data.begin());
      size_t size = 0;
      CHECK_NOTHROW(size = vbsim::fuzz::structured_mutate(format, data.data(), text.size(), kMaxSize, seed, keep_bytes));
      CHECK(size <= kMaxSize);
    }
  }
}
