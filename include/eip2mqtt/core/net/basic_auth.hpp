#pragma once
/// HTTP basic authentication (RFC 7617) as the metrics listener checks it: the one
/// `Authorization` header value its user and password make, compared in constant time.

#include <string>
#include <string_view>

namespace eip2mqtt::core::net {

/// `Basic ` and the base64 of `user:password` (UTF-8 as given), the header value a client sends.
std::string basic_authorization(std::string_view user, std::string_view password);

/// Whether `given` is `expected`, taking as long whatever the first difference: a client timing
/// the answers learns nothing of the password. (The length is not hidden: it is the header's.)
bool same_secret(std::string_view given, std::string_view expected);

}  // namespace eip2mqtt::core::net
