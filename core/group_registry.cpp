#include "group_registry.hpp"

#include <stdexcept>

#include "groups/mechanics_groups.hpp"
#include "groups/se3_group.hpp"
#include "groups/with_group.hpp"
#include "register_group.hpp"
#include "request_error.hpp"

namespace lienewton {
namespace {

// Every family a request may name. The rotation groups, SE(3) and the products with R^k are the service's own; a family added elsewhere
// (a test's group) registers itself with register_group<Family>() at static initialisation.
std::vector<std::unique_ptr<GroupFamily>>& families() {
  static std::vector<std::unique_ptr<GroupFamily>> all = [] {
    std::vector<std::unique_ptr<GroupFamily>> v;
    v.push_back(std::make_unique<FamilyOf<SOFamily>>());
    v.push_back(std::make_unique<FamilyOf<SEFamily>>());
    v.push_back(std::make_unique<FamilyOf<SOxRFamily>>());
    v.push_back(std::make_unique<FamilyOf<SExRFamily>>());
    v.push_back(std::make_unique<FamilyOf<SExRPowerFamily>>());
    return v;
  }();
  return all;
}

}  // namespace

const GroupFamily& group_family(const std::string& name) {
  for (const auto& f : families())
    if (f->name() == name) return *f;
  std::string names;
  for (const std::string& n : registered_group_names()) names += (names.empty() ? "" : ", ") + n;
  throw RequestError(RequestError::Kind::unprocessable, "group",
                     "group must be a registered group (" + names + "), got \"" + name + "\"");
}

std::vector<std::string> registered_group_names() {
  std::vector<std::string> names;
  for (const auto& f : families()) names.push_back(f->name());
  return names;
}

void add_group_family(std::unique_ptr<GroupFamily> family) {
  for (const auto& f : families())
    if (f->name() == family->name()) throw std::logic_error("group " + family->name() + " is registered twice");
  families().push_back(std::move(family));
}

}  // namespace lienewton
