// Provenance: SHA-256 against published test vectors, file digests, and the
// object every output records.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "provenance/file_digest.h"
#include "provenance/provenance.h"

namespace vbsim {
namespace {

TEST_CASE("SHA-256 matches the FIPS 180-2 examples", "[provenance]") {
  CHECK(sha256_hex("abc", 3) == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("", 0) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  const std::string two_blocks = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  CHECK(sha256_hex(two_blocks.data(), two_blocks.size()) ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST_CASE("a file's digest covers every block of it", "[provenance]") {
  const auto path = std::filesystem::temp_directory_path() / ("vbsim_digest_" + std::to_string(::getpid()));
  // One million 'a': the FIPS 180-2 long example, read in 1 MiB blocks (one full, one partial).
  std::ofstream(path) << std::string(1000000, 'a');
  const FileDigest d = sha256_file(path.string());
  CHECK(d.bytes == 1000000);
  CHECK(d.sha256 == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  std::filesystem::remove(path);
  CHECK_THROWS_WITH(sha256_file(path.string()), Catch::Contains(path.string()));
}

TEST_CASE("the provenance names the version, the command line and each input once", "[provenance]") {
  const char* argv[] = {"vbsim", "replay", "t.jsonl"};
  set_command_line(3, argv);
  const auto path = std::filesystem::temp_directory_path() / ("vbsim_prov_" + std::to_string(::getpid()));
  std::ofstream(path) << "abc";
  const nlohmann::json p = provenance_json({path.string(), std::string(), path.string()});
  std::filesystem::remove(path);
  CHECK(p["program"] == "vbsim");
  CHECK(p["version"] == vbsim_version());
  CHECK(!std::string(vbsim_revision()).empty());
  CHECK(p["command"] == nlohmann::json({"vbsim", "replay", "t.jsonl"}));
  REQUIRE(p["inputs"].size() == 1);  // the empty path is skipped, the repeated one listed once
  CHECK(p["inputs"][0]["bytes"] == 3);
  CHECK(p["inputs"][0]["sha256"] == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(vbsim_version_line() == std::string("vbsim ") + vbsim_version() + " (revision " + vbsim_revision() + ")");
}

TEST_CASE("an argument that is not UTF-8 still gives a provenance JSON can write", "[provenance]") {
  const char* argv[] = {"vbsim", "gen", "paths", "-o", "dir\xff"};
  set_command_line(5, argv);
  const std::string line = provenance_line({});
  CHECK_THAT(line, Catch::Contains("dir\xef\xbf\xbd"));  // U+FFFD
  CHECK(nlohmann::json::parse(line)["command"].size() == 5);
}

}  // namespace
}  // namespace vbsim
