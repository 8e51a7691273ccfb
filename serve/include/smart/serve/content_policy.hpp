// Contract: the Content-Security-Policy `smart serve` sends with every answer (issue 25: markup in
// an uploaded summary.json or a DDS host name ran as script in the viewer). Scripts only from the
// server's own files, plus the inline scripts of the app's index.html by their SHA-256 (CSP
// Level 3 "hash-source", https://www.w3.org/TR/CSP3/#grammardef-hash-source; the import map that
// names three.js is one), so markup smuggled into data could not run even if inserted as markup.
// Pure: the page's text in, the header's value out.
#pragma once

#include <string>
#include <string_view>

namespace smart::serve {

std::string content_security_policy(std::string_view index_html);
// 'sha256-<base64 of the digest>' of a script's text.
std::string script_hash_source(std::string_view script);

}  // namespace smart::serve
