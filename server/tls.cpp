#include "tls.hpp"

#include <cstdio>
#include <stdexcept>
#include <vector>

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>

namespace footpoint::server {

struct TlsCredentials::Loaded {
  X509* cert = nullptr;
  STACK_OF(X509) * chain = nullptr;  // the intermediates after the leaf in the certificate file
  EVP_PKEY* key = nullptr;
  Loaded() = default;
  Loaded(const Loaded&) = delete;
  Loaded& operator=(const Loaded&) = delete;
  ~Loaded() {
    X509_free(cert);
    sk_X509_pop_free(chain, X509_free);
    EVP_PKEY_free(key);
  }
};

namespace {

// OpenSSL's queued errors as one line (and the queue emptied).
std::string openssl_errors() {
  std::string text;
  while (const unsigned long e = ERR_get_error()) {
    char buf[256];
    ERR_error_string_n(e, buf, sizeof buf);
    (text += text.empty() ? "" : "; ") += buf;
  }
  return text.empty() ? std::string("no PEM data") : text;
}

struct BioCloser {
  void operator()(BIO* b) const { BIO_free(b); }
};

std::unique_ptr<BIO, BioCloser> open_file(const std::string& path) {
  std::unique_ptr<BIO, BioCloser> bio(BIO_new_file(path.c_str(), "r"));
  if (!bio) throw std::runtime_error("cannot read " + path + ": " + openssl_errors());
  return bio;
}

std::shared_ptr<const TlsCredentials::Loaded> read_credentials(const std::string& cert_path,
                                                               const std::string& key_path) {
  ERR_clear_error();
  auto loaded = std::make_shared<TlsCredentials::Loaded>();
  {
    auto bio = open_file(cert_path);
    loaded->cert = PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr);
    if (!loaded->cert) throw std::runtime_error(cert_path + ": no PEM certificate: " + openssl_errors());
    loaded->chain = sk_X509_new_null();
    while (X509* extra = PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr))
      sk_X509_push(loaded->chain, extra);
    ERR_clear_error();  // the end of the file
  }
  {
    auto bio = open_file(key_path);
    loaded->key = PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr);
    if (!loaded->key) throw std::runtime_error(key_path + ": no PEM private key: " + openssl_errors());
  }
  if (X509_check_private_key(loaded->cert, loaded->key) != 1)
    throw std::runtime_error(key_path + " is not the private key of the certificate in " + cert_path + ": " +
                             openssl_errors());
  return loaded;
}

// ECDHE key exchange with AEAD ciphers for TLS 1.2 (TLS 1.3's suites are all AEAD): Mozilla's
// "intermediate" server configuration.
constexpr const char* kTls12Ciphers =
    "ECDHE-ECDSA-AES128-GCM-SHA256:ECDHE-RSA-AES128-GCM-SHA256:ECDHE-ECDSA-AES256-GCM-SHA384:"
    "ECDHE-RSA-AES256-GCM-SHA384:ECDHE-ECDSA-CHACHA20-POLY1305:ECDHE-RSA-CHACHA20-POLY1305";

}  // namespace

TlsCredentials::TlsCredentials(std::string cert_path, std::string key_path)
    : cert_path_(std::move(cert_path)), key_path_(std::move(key_path)) {
  loaded_ = read_credentials(cert_path_, key_path_);
}

TlsCredentials::~TlsCredentials() = default;

std::shared_ptr<const TlsCredentials::Loaded> TlsCredentials::current() const {
  std::lock_guard lock(mutex_);
  return loaded_;
}

void TlsCredentials::reload() {
  auto fresh = read_credentials(cert_path_, key_path_);
  std::lock_guard lock(mutex_);
  loaded_ = std::move(fresh);
}

int TlsCredentials::on_certificate(SSL* ssl, void* self) {
  const auto loaded = static_cast<TlsCredentials*>(self)->current();
  // The SSL object takes its own references (override = 1 replaces what the context gave it).
  return SSL_use_cert_and_key(ssl, loaded->cert, loaded->key, loaded->chain, 1) == 1 ? 1 : 0;
}

bool TlsCredentials::configure(SSL_CTX& ctx) {
  SSL_CTX_set_options(&ctx, SSL_OP_NO_COMPRESSION | SSL_OP_NO_RENEGOTIATION |
                                SSL_OP_CIPHER_SERVER_PREFERENCE |
                                SSL_OP_NO_SESSION_RESUMPTION_ON_RENEGOTIATION);
  if (SSL_CTX_set_min_proto_version(&ctx, TLS1_2_VERSION) != 1) return false;
  if (SSL_CTX_set_cipher_list(&ctx, kTls12Ciphers) != 1) return false;
  const auto loaded = current();
  if (SSL_CTX_use_cert_and_key(&ctx, loaded->cert, loaded->key, loaded->chain, 1) != 1) return false;
  SSL_CTX_set_cert_cb(&ctx, &TlsCredentials::on_certificate, this);
  return true;
}

std::string TlsCredentials::describe() const {
  const auto loaded = current();
  std::string text;
  char subject[256] = {};
  X509_NAME_oneline(X509_get_subject_name(loaded->cert), subject, sizeof subject);
  text += subject;
  std::unique_ptr<BIO, BioCloser> bio(BIO_new(BIO_s_mem()));
  if (bio && ASN1_TIME_print(bio.get(), X509_get0_notAfter(loaded->cert)) == 1) {
    char* data = nullptr;
    const long n = BIO_get_mem_data(bio.get(), &data);
    text += ", valid until ";
    text.append(data, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace footpoint::server
