#include <boost/test/unit_test.hpp>

#include <string>

#include "pounding/io/sha256.hpp"

using pounding::io::Sha256;
using pounding::io::sha256_hex;

// The test vectors of FIPS 180-2, Appendix B (and its empty-message digest).
BOOST_AUTO_TEST_CASE(fips_180_2_vectors) {
  BOOST_TEST(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  BOOST_TEST(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  BOOST_TEST(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
             "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");  // 448 bits: two blocks of padding
  BOOST_TEST(sha256_hex(std::string(1'000'000, 'a')) ==
             "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// Fed in pieces that straddle the 64-byte blocks, the digest is that of the whole message.
BOOST_AUTO_TEST_CASE(pieces_hash_as_the_whole) {
  std::string message;
  for (int k = 0; k < 1000; ++k) message += static_cast<char>(k * 7 % 256);
  for (const std::size_t piece : {1u, 3u, 63u, 64u, 65u, 500u}) {
    Sha256 hash;
    for (std::size_t at = 0; at < message.size(); at += piece) hash.update(std::string_view(message).substr(at, piece));
    BOOST_TEST(hash.hex() == sha256_hex(message), "pieces of " << piece);
  }
}

// Messages of 55, 56 and 64 bytes put the length field at the end of the block, just past it,
// and into a block of its own: the padding's three cases (digests from Python's hashlib).
BOOST_AUTO_TEST_CASE(padding_boundaries) {
  BOOST_TEST(sha256_hex(std::string(55, 'a')) == "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  BOOST_TEST(sha256_hex(std::string(56, 'a')) == "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
  BOOST_TEST(sha256_hex(std::string(64, 'a')) == "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}
