// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bag/audit.hpp"

#include <sstream>

namespace quad::bag {

LossFigures& LossFigures::operator+=(const LossFigures& o)
{
  received += o.received;
  missing += o.missing;
  duplicated += o.duplicated;
  reordered += o.reordered;
  return *this;
}

void SequenceAudit::add(std::uint64_t writer, std::uint32_t vehicle, std::uint64_t seq)
{
  Writer& w = writers_[{writer, vehicle}];
  ++w.f.received;
  if (w.f.received == 1) {
    w.last = seq;  // a recorder joining late starts wherever the writer is
    return;
  }
  if (seq > w.last) {
    for (std::uint64_t s = w.last + 1; s < seq && w.gaps.size() < 1'000'000; ++s) {
      w.gaps.insert(s);
    }
    w.last = seq;
  } else if (w.gaps.erase(seq) == 1) {
    ++w.f.reordered;
  } else {
    ++w.f.duplicated;
  }
}

std::size_t SequenceAudit::writers() const
{
  std::set<std::uint64_t> ids;
  for (const auto& [key, w] : writers_) {
    ids.insert(key.first);
  }
  return ids.size();
}

LossFigures SequenceAudit::figures() const
{
  LossFigures total;
  for (const auto& [id, w] : writers_) {
    LossFigures f = w.f;
    f.missing = w.gaps.size();
    total += f;
  }
  return total;
}

std::string toText(const LossFigures& f, std::size_t writers)
{
  return "received " + std::to_string(f.received) + " missing " + std::to_string(f.missing) + " duplicated " +
         std::to_string(f.duplicated) + " reordered " + std::to_string(f.reordered) + " writers " +
         std::to_string(writers);
}

namespace {

struct LossText {
  LossFigures figures;
  std::optional<std::size_t> writers;  // when the text goes on to say
};

std::optional<LossText> parseLossText(std::string_view text)
{
  std::istringstream in{std::string(text)};
  LossText t;
  LossFigures& f = t.figures;
  const std::pair<const char*, std::uint64_t*> fields[] = {
      {"received", &f.received}, {"missing", &f.missing}, {"duplicated", &f.duplicated}, {"reordered", &f.reordered}};
  for (const auto& [name, value] : fields) {
    std::string word;
    if (!(in >> word >> *value) || word != name) {
      return std::nullopt;
    }
  }
  std::string word;
  std::size_t writers = 0;
  if (in >> word >> writers && word == "writers") {
    t.writers = writers;
  }
  return t;
}

}  // namespace

std::optional<LossFigures> parseLossFigures(std::string_view text)
{
  const auto t = parseLossText(text);
  return t ? std::optional<LossFigures>(t->figures) : std::nullopt;
}

std::optional<std::size_t> parseLossWriters(std::string_view text)
{
  const auto t = parseLossText(text);
  return t ? t->writers : std::nullopt;
}

}  // namespace quad::bag
