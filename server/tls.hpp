// TLS for the HTTP server (--tls-cert, --tls-key): a certificate chain and private key read from
// PEM files, offered by every handshake through OpenSSL's certificate callback
// (SSL_CTX_set_cert_cb), which takes the credentials held at that moment. reload() reads the files
// again and swaps the credentials: handshakes from then on present the new certificate, the
// connections already open keep theirs. Protocols: TLS 1.2 and 1.3 only, no compression, no
// renegotiation (RFC 8996 deprecates TLS 1.0 and 1.1).
#pragma once
#include <memory>
#include <mutex>
#include <string>

using SSL_CTX = struct ssl_ctx_st;
using SSL = struct ssl_st;

namespace footpoint::server {

class TlsCredentials {
 public:
  // Reads both files; throws std::runtime_error naming the file and OpenSSL's reason when either
  // cannot be read or the key is not the certificate's.
  TlsCredentials(std::string cert_path, std::string key_path);
  ~TlsCredentials();
  TlsCredentials(const TlsCredentials&) = delete;
  TlsCredentials& operator=(const TlsCredentials&) = delete;

  // Sets up a server context: protocol versions, options, ciphers, and the certificate callback
  // that presents the current credentials. Returns false when OpenSSL refuses.
  bool configure(SSL_CTX& ctx);
  // Reads the files again; on failure keeps the credentials in use and throws.
  void reload();
  // The current certificate's subject and notAfter (for the log).
  std::string describe() const;

  struct Loaded;

 private:
  static int on_certificate(SSL* ssl, void* self);
  std::shared_ptr<const Loaded> current() const;

  std::string cert_path_, key_path_;
  mutable std::mutex mutex_;
  std::shared_ptr<const Loaded> loaded_;
};

}  // namespace footpoint::server
