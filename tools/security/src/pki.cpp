// SPDX-License-Identifier: BSD-3-Clause
#include "quad/security/pki.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace quad::security {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what)
{
  const unsigned long code = ERR_get_error();
  char reason[256] = "no OpenSSL error";
  if (code != 0) {
    ERR_error_string_n(code, reason, sizeof(reason));
  }
  throw std::runtime_error(what + ": " + reason);
}

template <class T, void (*Free)(T*)>
struct Deleter {
  void operator()(T* p) const { Free(p); }
};
using Bio = std::unique_ptr<BIO, Deleter<BIO, BIO_free_all>>;
using Pkcs7 = std::unique_ptr<PKCS7, Deleter<PKCS7, PKCS7_free>>;
using Extension = std::unique_ptr<X509_EXTENSION, Deleter<X509_EXTENSION, X509_EXTENSION_free>>;

std::string drain(BIO* bio)
{
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio, &data);
  return std::string(data, static_cast<std::size_t>(size));
}

void addExtension(X509* cert, X509V3_CTX& ctx, int nid, const char* value)
{
  Extension ext(X509V3_EXT_conf_nid(nullptr, &ctx, nid, value));
  if (!ext || X509_add_ext(cert, ext.get(), -1) != 1) {
    fail(std::string("certificate extension ") + OBJ_nid2sn(nid) + " = " + value);
  }
}

void setName(X509_NAME* name, const std::string& common_name)
{
  const auto* org = reinterpret_cast<const unsigned char*>("quad");
  const auto* cn = reinterpret_cast<const unsigned char*>(common_name.c_str());
  if (X509_NAME_add_entry_by_txt(name, "O", MBSTRING_UTF8, org, -1, -1, 0) != 1 ||
      X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_UTF8, cn, -1, -1, 0) != 1) {
    fail("certificate name CN=" + common_name);
  }
}

std::uint64_t nextSerial()
{
  // Unique within a run and across runs: time-based high bits, a counter low.
  static std::atomic<std::uint64_t> counter{0};
  const auto seconds = static_cast<std::uint64_t>(Clock::to_time_t(Clock::now()));
  return (seconds << 20) | (counter++ & 0xfffff);
}

}  // namespace

struct KeyPair::Impl {
  X509* cert = nullptr;
  EVP_PKEY* key = nullptr;
  ~Impl()
  {
    X509_free(cert);
    EVP_PKEY_free(key);
  }
};

KeyPair::KeyPair() : impl_(std::make_unique<Impl>()) {}
KeyPair::~KeyPair() = default;
KeyPair::KeyPair(KeyPair&&) noexcept = default;
KeyPair& KeyPair::operator=(KeyPair&&) noexcept = default;

namespace {

/// A certificate for a new P-256 key, issued by `issuer` (itself when null).
void issue(KeyPair::Impl& out, const KeyPair::Impl* issuer, const std::string& common_name, bool authority,
           Clock::time_point not_before, Clock::time_point not_after)
{
  out.key = EVP_EC_gen("P-256");
  if (out.key == nullptr) {
    fail("P-256 key for " + common_name);
  }
  out.cert = X509_new();
  if (out.cert == nullptr || X509_set_version(out.cert, 2) != 1 ||
      ASN1_INTEGER_set_uint64(X509_get_serialNumber(out.cert), nextSerial()) != 1) {
    fail("certificate for " + common_name);
  }
  setName(X509_get_subject_name(out.cert), common_name);
  const X509* signer_cert = issuer != nullptr ? issuer->cert : out.cert;
  EVP_PKEY* signer_key = issuer != nullptr ? issuer->key : out.key;
  if (X509_set_issuer_name(out.cert, X509_get_subject_name(signer_cert)) != 1 ||
      ASN1_TIME_set(X509_getm_notBefore(out.cert), Clock::to_time_t(not_before)) == nullptr ||
      ASN1_TIME_set(X509_getm_notAfter(out.cert), Clock::to_time_t(not_after)) == nullptr ||
      X509_set_pubkey(out.cert, out.key) != 1) {
    fail("certificate for " + common_name);
  }
  X509V3_CTX ctx;
  X509V3_set_ctx_nodb(&ctx);
  X509V3_set_ctx(&ctx, const_cast<X509*>(signer_cert), out.cert, nullptr, nullptr, 0);
  addExtension(out.cert, ctx, NID_basic_constraints, authority ? "critical,CA:TRUE" : "critical,CA:FALSE");
  addExtension(out.cert, ctx, NID_key_usage,
               authority ? "critical,keyCertSign,cRLSign,digitalSignature" : "critical,digitalSignature,keyAgreement");
  addExtension(out.cert, ctx, NID_subject_key_identifier, "hash");
  if (X509_sign(out.cert, signer_key, EVP_sha256()) == 0) {
    fail("signing the certificate of " + common_name);
  }
}

}  // namespace

KeyPair KeyPair::makeAuthority(const std::string& common_name, Clock::time_point not_before,
                               Clock::time_point not_after)
{
  KeyPair k;
  issue(*k.impl_, nullptr, common_name, true, not_before, not_after);
  return k;
}

KeyPair KeyPair::makeIdentity(const KeyPair& authority, const std::string& common_name, Clock::time_point not_before,
                              Clock::time_point not_after)
{
  KeyPair k;
  issue(*k.impl_, authority.impl_.get(), common_name, false, not_before, not_after);
  return k;
}

KeyPair KeyPair::load(const fs::path& certificate, const fs::path& key)
{
  KeyPair k;
  Bio cert_in(BIO_new_file(certificate.c_str(), "r"));
  if (!cert_in || (k.impl_->cert = PEM_read_bio_X509(cert_in.get(), nullptr, nullptr, nullptr)) == nullptr) {
    fail("cannot read a PEM certificate from " + certificate.string());
  }
  Bio key_in(BIO_new_file(key.c_str(), "r"));
  if (!key_in || (k.impl_->key = PEM_read_bio_PrivateKey(key_in.get(), nullptr, nullptr, nullptr)) == nullptr) {
    fail("cannot read a PEM private key from " + key.string());
  }
  if (X509_check_private_key(k.impl_->cert, k.impl_->key) != 1) {
    fail(key.string() + " is not the key of " + certificate.string());
  }
  return k;
}

void KeyPair::save(const fs::path& certificate, const fs::path& key) const
{
  Bio cert_out(BIO_new(BIO_s_mem()));
  Bio key_out(BIO_new(BIO_s_mem()));
  if (!cert_out || !key_out || PEM_write_bio_X509(cert_out.get(), impl_->cert) != 1 ||
      PEM_write_bio_PrivateKey(key_out.get(), impl_->key, nullptr, nullptr, 0, nullptr, nullptr) != 1) {
    fail("encoding " + certificate.string());
  }
  writeFile(certificate, drain(cert_out.get()), fs::perms::owner_read | fs::perms::owner_write |
                                                    fs::perms::group_read | fs::perms::others_read);
  writeFile(key, drain(key_out.get()), fs::perms::owner_read | fs::perms::owner_write);
}

std::string KeyPair::subject() const
{
  Bio out(BIO_new(BIO_s_mem()));
  if (!out || X509_NAME_print_ex(out.get(), X509_get_subject_name(impl_->cert), 0, XN_FLAG_RFC2253) < 0) {
    fail("printing a certificate's subject");
  }
  return drain(out.get());
}

std::string KeyPair::signSmime(const std::string& text) const
{
  constexpr int kFlags = PKCS7_DETACHED | PKCS7_TEXT;
  Bio in(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
  Pkcs7 p7(PKCS7_sign(impl_->cert, impl_->key, nullptr, in.get(), kFlags));
  if (!p7) {
    fail("signing a document");
  }
  Bio again(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
  Bio out(BIO_new(BIO_s_mem()));
  if (!again || !out || SMIME_write_PKCS7(out.get(), p7.get(), again.get(), kFlags) != 1) {
    fail("writing a signed document");
  }
  return drain(out.get());
}

void writeFile(const fs::path& path, const std::string& content, fs::perms mode)
{
  // Created with its mode, so a key is never readable by others, not even for a moment.
  const fs::path partial = path.string() + ".partial";
  ::unlink(partial.c_str());
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, static_cast<mode_t>(mode));
  if (fd < 0) {
    throw std::runtime_error("cannot create " + partial.string() + ": " + std::strerror(errno));
  }
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      throw std::runtime_error("cannot write " + partial.string() + ": " + std::strerror(error));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0 || ::rename(partial.c_str(), path.c_str()) != 0) {
    throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
  }
}

}  // namespace quad::security
