#include "smart/serve/content_policy.hpp"

#include <openssl/evp.h>
#include <openssl/sha.h>

#include <vector>

namespace smart::serve {

std::string script_hash_source(std::string_view script) {
  unsigned char digest[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>(script.data()), script.size(), digest);
  std::vector<unsigned char> b64(4 * ((SHA256_DIGEST_LENGTH + 2) / 3) + 1);
  const int n = EVP_EncodeBlock(b64.data(), digest, SHA256_DIGEST_LENGTH);
  return "'sha256-" + std::string(reinterpret_cast<char*>(b64.data()), static_cast<size_t>(n)) +
         "'";
}

std::string content_security_policy(std::string_view html) {
  std::string scripts = "'self'";
  // Inline scripts: <script ...>text</script> without a src attribute.
  for (std::size_t at = html.find("<script"); at != std::string_view::npos;
       at = html.find("<script", at + 1)) {
    const auto open_end = html.find('>', at);
    const auto close = html.find("</script>", open_end);
    if (open_end == std::string_view::npos || close == std::string_view::npos) break;
    if (html.substr(at, open_end - at).find(" src=") != std::string_view::npos) continue;
    scripts += " " + script_hash_source(html.substr(open_end + 1, close - open_end - 1));
  }
  return "default-src 'self'; script-src " + scripts +
         "; style-src 'self'; img-src 'self' data: blob:; connect-src 'self'; object-src 'none'; "
         "base-uri 'none'; frame-ancestors 'none'; form-action 'self'";
}

}  // namespace smart::serve
