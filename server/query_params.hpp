#pragma once
// GET forms of the API (EventSource, <img src>) carry the request as query parameters that mirror the JSON
// fields. Each value is read as JSON when it is a JSON number, true/false, or a bracketed array/object
// (e.g. h=[0.25,0.5] or z=[[1,0,0],[0,1,0],[0,0,1]]); a comma-separated list (n=3,4,5) becomes an array;
// anything else is a string. The resulting object then goes through the same codec as a POST body.
#include <map>
#include <set>
#include <string>

#include "core/fields.hpp"
#include "server/json_codec.hpp"

namespace lienewton::service {

// list_fields are array-valued in the JSON request: a single value there becomes a one-element array
// (methods=newton-group). Throws FieldError (duplicate_field / invalid_field) naming the parameter.
// The array-valued fields of the given routes (their rows and their picture options): sweep's methods, n, h.
std::set<std::string> list_fields(fields::Routes routes);

json query_to_json(const std::multimap<std::string, std::string>& params, const std::set<std::string>& list_fields = {});

}  // namespace lienewton::service
