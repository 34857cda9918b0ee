// The tally's counting and the gate's lines.
#include "oblique/run/tally.h"

#include <cmath>

#include <algorithm>
#include <tuple>

namespace oblique::run {

bool operator<(const Kind& a, const Kind& b) {
  return std::tie(a.axis, a.name) < std::tie(b.axis, b.name);
}

bool operator==(const Kind& a, const Kind& b) {
  return a.axis == b.axis && a.name == b.name;
}

void Tally::made(const std::vector<Kind>& kinds) {
  for (const Kind& k : kinds) ++counts_[k].made;
}

void Tally::judged(const std::vector<Kind>& kinds, long n) {
  judged_ += n;
  for (const Kind& k : kinds) counts_[k].judged += n;
}

void Tally::left_out(const std::vector<Kind>& kinds, const std::string& why, bool claimed, long n) {
  left_out_ += n;
  reasons_[why] += n;
  for (const Kind& k : kinds) {
    Counts& c = counts_[k];
    c.left_out += n;
    if (!claimed) c.unclaimed += n;
  }
}

void Tally::refused(const std::vector<Kind>& kinds, const std::string& by) {
  if (std::find(refusers_.begin(), refusers_.end(), by) == refusers_.end()) refusers_.push_back(by);
  for (const Kind& k : kinds) ++counts_[k].refused;
}

void Tally::not_applicable(const std::vector<Kind>& kinds, const std::string& why, long n) {
  not_applicable_[why] += n;
  for (const Kind& k : kinds) counts_[k].not_applicable += n;
}

Counts Tally::of(const Kind& kind) const {
  const auto it = counts_.find(kind);
  return it == counts_.end() ? Counts{} : it->second;
}

std::map<std::string, long> Tally::by(const std::string& axis, long Counts::*count) const {
  std::map<std::string, long> out;
  for (const auto& [kind, counts] : counts_) {
    if (kind.axis == axis && counts.*count > 0) out[kind.name] = counts.*count;
  }
  return out;
}

std::vector<Kind> Tally::met(const std::string& axis) const {
  std::vector<Kind> out;
  for (const auto& [kind, counts] : counts_) {
    if (kind.axis == axis) out.push_back(kind);
  }
  return out;
}

std::vector<Kind> claims_of(const Contract& contract) {
  std::vector<Kind> out;
  for (const cases::Family f : contract.families)
    out.push_back({"family", std::string(cases::family_name(f))});
  for (const Convention c : contract.conventions)
    out.push_back({"convention", std::string(convention_name(c))});
  return out;
}

namespace {

std::string list_of(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> unjudged(const Tally& tally, const std::vector<Kind>& claims, long rounds,
                                  const Advice& advice) {
  std::vector<std::string> out;
  for (const Kind& kind : claims) {
    const Counts c = tally.of(kind);
    if (c.judged > 0) continue;
    std::string line = advice.claimant + " " + kind.axis + " " + kind.name + ", and no " +
                       advice.unit + " of it was judged: ";
    const std::string leave = advice.leave_out(kind);
    if (c.made == 0 && c.left_out == 0 && c.refused == 0 && c.not_applicable == 0) {
      line += (advice.none_drawn.empty()
                   ? "none was drawn in " + std::to_string(rounds) + " " + advice.rounds
                   : advice.none_drawn) +
              ": " + advice.more + ", or " + leave;
    } else if (c.left_out == 0 && c.refused == 0 && c.not_applicable > 0) {
      line += "it applies to none of the " + std::to_string(c.not_applicable) + " " +
              advice.rounds + " (" + counts_text(tally.not_applicable_reasons()) + "): " + leave +
              (advice.applicable.empty() ? "" : ", or " + advice.applicable);
    } else if (c.refused > 0 && c.left_out == 0) {
      line += (c.made == 0 || c.refused == c.made ? "all " : "") + std::to_string(c.refused) +
              " refused by accepts (" + list_of(tally.refusers()) + "): " + advice.widen_accepts +
              ", or " + leave;
    } else {
      line += (c.refused > 0 ? std::to_string(c.refused) + " refused by accepts, " : "all ") +
              std::to_string(c.left_out) +
              " left out (why, over the run: " + counts_text(tally.reasons()) +
              "): " + (advice.judge_left_out.empty() ? advice.more : advice.judge_left_out) +
              ", or " + leave;
    }
    out.push_back(std::move(line));
  }
  return out;
}

bool left_out_beyond(long left, long drawn, double share) {
  if (left < 2 || drawn <= 0) return false;  // one case left out is no pattern
  // The Wilson score interval's lower end at z = 3.29 (one-sided 99.95%): a run tests every kind
  // it claims (families, conventions, properties: dozens), so each test takes a small error rate.
  const double n = static_cast<double>(drawn), p = static_cast<double>(left) / n, z = 3.29;
  const double centre = p + z * z / (2 * n);
  const double spread = z * std::sqrt(p * (1 - p) / n + z * z / (4 * n * n));
  return (centre - spread) / (1 + z * z / n) > share;
}

std::string partly_judged(const Tally& tally, const std::vector<Kind>& claims, double share,
                          bool with_axis) {
  std::string out;
  for (const Kind& kind : claims) {
    const Counts c = tally.of(kind);
    const long left = c.left_out - c.unclaimed;  // of what the contract claims
    if (c.judged == 0 || !left_out_beyond(left, c.judged + left, share)) continue;
    out += (out.empty() ? "" : ", ") + (with_axis ? kind.axis + " " : std::string()) + kind.name +
           " " + std::to_string(left) + " of " + std::to_string(c.judged + left);
  }
  return out;
}

std::string partly_judged_warning(const std::string& partly, bool strict) {
  return "warning: judged in part only: more than " +
         std::to_string(static_cast<int>(100 * kLeftOutWarning + 0.5)) + "% left out: " + partly +
         (strict ? " [--strict: not a pass]" : " [--strict makes it a failure]") + "\n";
}

std::string counts_text(const std::map<std::string, long>& counts) {
  std::string out;
  for (const auto& [name, n] : counts)
    out += (out.empty() ? "" : ", ") + name + " " + std::to_string(n);
  return out.empty() ? "none" : out;
}

}  // namespace oblique::run
