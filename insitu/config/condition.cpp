// The condition's scan and muparser. The scan finds the reductions and the words and writes
// each in place as a text of the same length that muparser reads (a reduction becomes a
// variable "_r0____", `and` "&& "), so that a position muparser reports is the user's own.
#include "insitu/config/condition.h"

#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <regex>
#include <set>
#include <vector>

#include "sim_adapter/near_name.h"

namespace voxspan {
namespace {

constexpr std::string_view kReductionHelp =
    "min(a), max(a), sum(a), mean(a) of an attribute a or x, y, z, and count(), each with a box "
    "as its last argument or not";

bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

double not_of(double v) { return v == 0 ? 1 : 0; }

std::string joined(const std::vector<std::string_view>& names) {
  std::string text;
  for (std::string_view n : names) text.append(text.empty() ? "" : ", ").append(n);
  return text;
}

// "unknown <what> \"<name>\" (did you mean \"<near>\"? <list>)".
std::string unknown(std::string_view what, std::string_view name,
                    const std::vector<std::string_view>& known, std::string_view list) {
  const std::string near = near_name(name, known);
  std::string text = "unknown " + std::string(what) + " \"" + std::string(name) + "\" (";
  if (!near.empty()) text += "did you mean \"" + near + "\"? ";
  return text + std::string(list) + ")";
}

// Reads the expression, rewriting its reductions and words for muparser in place.
class Scan {
 public:
  Scan(std::string_view text, const mu::Parser& parser,
       const std::map<std::string, double>& constants,
       const std::map<std::string, ConditionBox>& boxes)
      : in_(text), out_(text), boxes_(boxes) {
    for (const auto& [name, f] : parser.GetFunDef())
      if (!value_of(kReductionNames, name)) functions_.push_back(name);
    variables_ = {"time", "step"};
    for (const auto& [name, v] : constants) variables_.push_back(name);
    for (const auto& [name, v] : parser.GetConst()) variables_.push_back(name);
    for (const auto& [name, b] : boxes) box_names_.push_back(name);
  }

  void run() {
    for (std::size_t i = 0; i < in_.size();) {
      if (digit(in_[i]) || (in_[i] == '.' && i + 1 < in_.size() && digit(in_[i + 1])))
        i = skip_number(i);
      else if (name_start(in_[i])) i = name(i);
      else i = symbol(i);
    }
  }

  const std::string& rewritten() const { return out_; }
  const std::vector<Reduction>& reductions() const { return reductions_; }
  // The variable names standing for reduction i (one per length it was written with).
  const std::vector<std::pair<std::string, std::size_t>>& placeholders() const {
    return placeholders_;
  }

 private:
  std::size_t skip_number(std::size_t i) const {
    while (i < in_.size() && (digit(in_[i]) || in_[i] == '.')) ++i;
    if (i < in_.size() && (in_[i] == 'e' || in_[i] == 'E')) {
      std::size_t j = i + 1;
      if (j < in_.size() && (in_[j] == '+' || in_[j] == '-')) ++j;
      if (j < in_.size() && digit(in_[j])) i = j;
      while (i < in_.size() && digit(in_[i])) ++i;
    }
    return i;
  }

  std::size_t skip_spaces(std::size_t i) const {
    while (i < in_.size() && std::isspace(static_cast<unsigned char>(in_[i]))) ++i;
    return i;
  }

  std::size_t name(std::size_t begin) {
    std::size_t end = begin;
    while (end < in_.size() && name_char(in_[end])) ++end;
    const std::string_view word = in_.substr(begin, end - begin);
    const std::size_t next = skip_spaces(end);
    const bool call = next < in_.size() && in_[next] == '(';
    if (word == "and" || word == "or" || word == "not") {
      out_.replace(begin, word.size(), word == "and" ? "&& " : word == "or" ? "||" : "!  ");
      return end;
    }
    if (const auto op = value_of(kReductionNames, word); op && call)
      return reduction(*op, begin, next);
    if (call) {
      if (std::find(functions_.begin(), functions_.end(), word) == functions_.end())
        throw ConditionError(unknown("function", word, functions_,
                                     "reductions: " + std::string(kReductionHelp) +
                                         "; functions: " + joined(functions_)),
                             begin);
    } else if (std::find(variables_.begin(), variables_.end(), word) == variables_.end()) {
      throw ConditionError(
          unknown("name", word, variables_,
                  "names: " + joined(variables_) + "; reductions: " + std::string(kReductionHelp)),
          begin);
    }
    return end;
  }

  // A single '=' would assign (muparser's): the mistake for ==.
  std::size_t symbol(std::size_t i) const {
    if (in_[i] == '=') {
      const bool after_comparison =
          i > 0 && std::string_view("=<>!").find(in_[i - 1]) != std::string_view::npos;
      const bool before_equal = i + 1 < in_.size() && in_[i + 1] == '=';
      if (!after_comparison && !before_equal)
        throw ConditionError("\"=\" is not a comparison: write \"==\"", i);
    }
    return i + 1;
  }

  // `op(` at begin..open: its arguments are names, the attribute and the box.
  std::size_t reduction(ReductionOp op, std::size_t begin, std::size_t open) {
    std::vector<std::pair<std::string_view, std::size_t>> args;
    std::size_t i = skip_spaces(open + 1);
    const std::string shape = op == ReductionOp::count
                                  ? "count() or count(box)"
                                  : std::string(name_of(kReductionNames, op)) + "(attribute) or " +
                                        std::string(name_of(kReductionNames, op)) +
                                        "(attribute, box)";
    while (i < in_.size() && in_[i] != ')') {
      if (!args.empty()) {
        if (in_[i] != ',') break;
        i = skip_spaces(i + 1);
      }
      std::size_t end = i;
      while (end < in_.size() && name_char(in_[end])) ++end;
      if (end == i || !name_start(in_[i])) break;
      args.emplace_back(in_.substr(i, end - i), i);
      i = skip_spaces(end);
    }
    const std::size_t most = op == ReductionOp::count ? 1 : 2;
    const std::size_t least = op == ReductionOp::count ? 0 : 1;
    if (i >= in_.size() || in_[i] != ')' || args.size() < least || args.size() > most)
      throw ConditionError("expected " + shape + " (names, not expressions)",
                           i < in_.size() ? i : begin);
    Reduction r{op, {}, {}};
    if (op != ReductionOp::count) r.attribute = args.front().first;
    if (op != ReductionOp::count && boxes_.count(r.attribute) > 0)
      throw ConditionError("\"" + r.attribute + "\" is a box, not an attribute: " + shape,
                           args.front().second);
    if (args.size() == least + 1) r.box = box(args.back().first, args.back().second);
    return place(std::move(r), begin, i + 1);
  }

  std::string box(std::string_view name, std::size_t at) const {
    if (boxes_.count(std::string(name)) == 0)
      throw ConditionError(unknown("box", name, box_names_,
                                   box_names_.empty() ? "the config names none in `boxes`"
                                                      : "boxes: " + joined(box_names_)),
                           at);
    return std::string(name);
  }

  // Writes reduction r over begin..end as "_r<index>" padded with '_' to the same length.
  std::size_t place(Reduction r, std::size_t begin, std::size_t end) {
    std::size_t index = std::find(reductions_.begin(), reductions_.end(), r) - reductions_.begin();
    if (index == reductions_.size()) reductions_.push_back(std::move(r));
    std::string name = "_r" + std::to_string(index);
    if (name.size() > end - begin) throw ConditionError("too many reductions", begin);
    name.resize(end - begin, '_');
    out_.replace(begin, name.size(), name);
    placeholders_.emplace_back(name, index);
    return end;
  }

  std::string_view in_;
  std::string out_;
  const std::map<std::string, ConditionBox>& boxes_;
  std::vector<std::string_view> functions_, variables_, box_names_;
  std::vector<Reduction> reductions_;
  std::vector<std::pair<std::string, std::size_t>> placeholders_;
};

// muparser's message in the user's words: no position (the caller's line:col says it), a
// reduction's variable shown as the user wrote it.
std::string message_of(const mu::Parser::exception_type& e, std::string_view text) {
  std::string m =
      std::regex_replace(e.GetMsg(), std::regex(" *(found )?at position [0-9]+\\.?"), "");
  const std::string token = e.GetToken();
  if (token.rfind("_r", 0) == 0 && e.GetPos() < int(text.size())) {
    const std::string original(text.substr(std::size_t(e.GetPos()), token.size()));
    for (std::size_t at = m.find(token); at != std::string::npos; at = m.find(token, at + 1))
      m.replace(at, token.size(), original);
  }
  if (!m.empty()) m[0] = char(std::tolower(static_cast<unsigned char>(m[0])));
  return m;
}

}  // namespace

std::string name_problem(std::string_view name) {
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0])) ||
      !std::all_of(name.begin(), name.end(), name_char))
    return "must be a letter, then letters, digits or '_'";
  static const mu::Parser parser;
  const std::string n(name);
  if (n == "time" || n == "step" || n == "and" || n == "or" || n == "not" ||
      value_of(kReductionNames, n) || parser.GetFunDef().count(n) > 0)
    return "is a name the conditions have already (time, step, and, or, not, the reductions and "
           "muparser's functions)";
  return {};
}

std::string Reduction::text() const {
  std::string t(name_of(kReductionNames, op));
  t += "(" + attribute;
  if (!box.empty()) t += (attribute.empty() ? "" : ", ") + box;
  return t + ")";
}

struct Condition::Impl {
  mu::Parser parser;
  std::vector<Reduction> reductions;
  std::vector<double> inputs;
  double step = 0, time = 0;
};

Condition::Condition(std::string_view text, const std::map<std::string, double>& constants,
                     const std::map<std::string, ConditionBox>& boxes)
    : impl_(std::make_unique<Impl>()) {
  mu::Parser& p = impl_->parser;
  Scan scan(text, p, constants, boxes);
  scan.run();
  impl_->reductions = scan.reductions();
  impl_->inputs.assign(impl_->reductions.size(), std::numeric_limits<double>::quiet_NaN());
  try {
    p.DefineInfixOprt("!", not_of);
    p.DefineVar("time", &impl_->time);
    p.DefineVar("step", &impl_->step);
    for (const auto& [name, value] : constants) p.DefineConst(name, value);
    for (const auto& [name, index] : scan.placeholders()) p.DefineVar(name, &impl_->inputs[index]);
    p.SetExpr(scan.rewritten());
    p.Eval();  // parses into muparser's byte code: later calls only run it
  } catch (const mu::Parser::exception_type& e) {
    const std::size_t at = e.GetPos() >= 0 ? std::size_t(e.GetPos()) : 0;
    throw ConditionError(message_of(e, text), std::min(at, text.size()));
  }
}

Condition::Condition(Condition&&) noexcept = default;
Condition& Condition::operator=(Condition&&) noexcept = default;
Condition::~Condition() = default;

std::span<const Reduction> Condition::reductions() const { return impl_->reductions; }
std::span<double> Condition::inputs() { return impl_->inputs; }

bool Condition::holds(std::int64_t step, double time) {
  impl_->step = double(step);
  impl_->time = time;
  const double v = impl_->parser.Eval();
  return v != 0 && !std::isnan(v);
}

}  // namespace voxspan
