// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The certificates and signatures DDS Security's builtin plugins need, made with OpenSSL's
/// libcrypto: a certificate authority, identities it signs (ECDSA P-256 keys), and S/MIME
/// signatures of governance and permissions documents. No DDS here.

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

namespace quad::security {

using Clock = std::chrono::system_clock;

/// A certificate and its private key, loaded or freshly made.
class KeyPair {
public:
  KeyPair();
  ~KeyPair();
  KeyPair(KeyPair&&) noexcept;
  KeyPair& operator=(KeyPair&&) noexcept;

  /// A self-signed authority "O=quad, CN=<common_name>", valid over [not_before, not_after].
  static KeyPair makeAuthority(const std::string& common_name, Clock::time_point not_before,
                               Clock::time_point not_after);

  /// An identity "O=quad, CN=<common_name>" signed by `authority`.
  static KeyPair makeIdentity(const KeyPair& authority, const std::string& common_name, Clock::time_point not_before,
                              Clock::time_point not_after);

  /// Reads a PEM certificate and key; throws std::runtime_error naming the file.
  static KeyPair load(const std::filesystem::path& certificate, const std::filesystem::path& key);

  /// Writes the certificate (0644) and the private key (0600) as PEM; throws naming the file.
  void save(const std::filesystem::path& certificate, const std::filesystem::path& key) const;

  /// The subject as DDS Security's permissions name it (RFC 2253: "CN=plant,O=quad").
  std::string subject() const;

  /// Signs `text` as S/MIME (multipart/signed, text/plain), as `openssl smime -sign -text`
  /// does: what the builtin access control plugin verifies.
  std::string signSmime(const std::string& text) const;

  struct Impl;  // the OpenSSL objects (pki.cpp)

private:
  std::unique_ptr<Impl> impl_;
};

/// Writes `content` to `path` with `mode`, replacing it; throws naming the file.
void writeFile(const std::filesystem::path& path, const std::string& content, std::filesystem::perms mode);

}  // namespace quad::security
