#include "core/shard.hpp"

#include <charconv>

#include "core/errors.hpp"

namespace cullcheck {

namespace {
bool whole_number(const std::string& text, std::size_t& out) {
  if (text.empty() || text.size() > 6) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
  return error == std::errc() && end == text.data() + text.size();
}
}  // namespace

Shard parse_shard(const std::string& text, const std::string& flag) {
  const std::size_t slash = text.find('/');
  Shard s;
  if (slash == std::string::npos || !whole_number(text.substr(0, slash), s.index) ||
      !whole_number(text.substr(slash + 1), s.count))
    throw InputError("flag", flag, "'" + text + "' is not K/N (shard K of N, counted from 0, e.g. 0/4)");
  if (s.count < 1 || s.count > 10000) throw InputError("flag", flag, "'" + text + "': N must be from 1 to 10000");
  if (s.index >= s.count)
    throw InputError("flag", flag, "'" + text + "': K must be below N (shards are numbered 0 to " + std::to_string(s.count - 1) + ")");
  return s;
}

}  // namespace cullcheck
