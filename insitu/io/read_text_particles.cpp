// Particles from text files.
//  .csv: a header row names the columns (ParaView's "Save Data" CSV works as is), or, where the
//        first row holds numbers, the '#' comment line just before it with as many names
//        (numpy.savetxt's header), else the columns are x, y, z, column4... (said in `chosen`).
//        Columns x, y and z may stand apart in any order (x and y alone: a 2D run, z = 0, said in
//        `chosen`); an empty field is NaN (pandas);
//        an unnamed column (pandas' index) is column<k>; Excel's byte-order mark is skipped.
//        Fields are separated by commas, else semicolons (DualSPHysics), else tabs, else white
//        space, as the first row has them; a unit after a name ("Pos.x [m]") is left out of it.
//        Positions are x,y,z or Points:0,Points:1,Points:2 (any case); three consecutive columns
//        named <base>_x/_y/_z, <base>:0/:1/:2, <base>.x/.y/.z or <base>x/y/z become the vector
//        attribute <base> (u, v, w: "velocity"); a column radius/radii/r gives the radii; every
//        other column is a scalar attribute.
//  .xyz: whitespace-separated "x y z [radius] [more...]" per line, '#' comments; the
//        extended-XYZ header (a count line, then a comment line) and a leading element symbol
//        on each line are accepted. Extra columns become attributes column4, column5... A
//        comment line with extended XYZ's Properties=name:type:count:... (ASE, OVITO) names the
//        columns instead: pos the positions, radius/radii/r the radii, other R and I columns
//        attributes (3 wide: a vector), S and L columns (species, flags) skipped.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cctype>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "insitu/io/particle_data.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

// A CSV field without its surrounding spaces and quotes.
std::string field_text(std::string_view s) {
  std::string out = trim(s);
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"')
    out = out.substr(1, out.size() - 2);
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A field's number; an empty field is a missing value, NaN (pandas writes NaN so).
bool parse_number(std::string_view text, double& out) {
  std::string t = field_text(text);
  if (t.empty()) {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const char* b = t.data();
  const char* e = b + t.size();
  if (b != e && *b == '+') ++b;
  auto [end, ec] = std::from_chars(b, e, out);
  return ec == std::errc() && end == e && b != e;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == sep && !quoted) {
      fields.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  fields.push_back(field);
  return fields;
}

std::vector<std::string> split_whitespace(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t b = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > b) fields.push_back(line.substr(b, i - b));
  }
  return fields;
}

// A CSV row's separator, from its first row: kWhiteSpace for runs of spaces and tabs.
constexpr char kWhiteSpace = ' ';
char separator_of(const std::string& row) {
  for (char c : {',', ';', '\t'})
    if (row.find(c) != std::string::npos) return c;
  return kWhiteSpace;
}

// A trimmed row's fields. `closed`: every row ends with a separator that opens no field
// (DualSPHysics'); otherwise one at the end opens an empty last field (pandas' NaN).
std::vector<std::string> fields_of(const std::string& row, char sep, bool closed = false) {
  if (sep == kWhiteSpace) return split_whitespace(row);
  return split(closed && !row.empty() && row.back() == sep ? row.substr(0, row.size() - 1) : row,
               sep);
}

// A column's name without a unit after it: "Vel.x [m/s]" is "Vel.x"; "f[0]" (no space before
// the bracket) is a component, kept.
std::string without_unit(std::string name) {
  const std::size_t open = name.find_last_of("[(");
  if (open == std::string::npos || open == 0 || name[open - 1] != ' ') return name;
  if (name.back() == (name[open] == '[' ? ']' : ')')) name = trim(name.substr(0, open));
  return name;
}

// The base name when a, b, c are the x, y, z components of one vector; empty otherwise. PySPH's
// u, v, w (its saved columns) are "velocity", as its HDF5 files read.
std::string vector_base(const std::string& a, const std::string& b, const std::string& c) {
  if (lower(a) == "u" && lower(b) == "v" && lower(c) == "w") return "velocity";
  static const std::vector<std::array<std::string, 3>> suffixes = {
      {"_x", "_y", "_z"}, {":0", ":1", ":2"}, {"[0]", "[1]", "[2]"},
      {"_0", "_1", "_2"}, {".x", ".y", ".z"}, {"x", "y", "z"}};
  std::string la = lower(a), lb = lower(b), lc = lower(c);
  for (const auto& s : suffixes) {
    auto ends = [](const std::string& t, const std::string& suffix) {
      return t.size() > suffix.size() &&
             t.compare(t.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    if (!ends(la, s[0]) || !ends(lb, s[1]) || !ends(lc, s[2])) continue;
    std::string base = a.substr(0, a.size() - s[0].size());
    if (lower(base) == lb.substr(0, lb.size() - s[1].size()) &&
        lower(base) == lc.substr(0, lc.size() - s[2].size()))
      return base;
  }
  return "";
}

bool is_position_base(const std::string& base) {
  std::string b = lower(base);
  return b == "points" || b == "position" || b == "positions" || b == "pos" || b == "coords";
}

// A column group of the CSV: a scalar (one column) or a vector (three).
struct Column {
  std::string name;
  std::size_t first;
  int components;
};

std::ifstream open_text(const std::filesystem::path& path) {
  require_particle_file(path);
  std::ifstream in(path);
  if (!in) throw make_error("cannot read particles from ", path.string(), ": cannot open the file");
  return in;
}

}  // namespace

ParticleData read_csv_particles(const std::filesystem::path& path) {
  std::ifstream in = open_text(path);
  auto fail = [&](std::size_t line, const std::string& why) {
    return make_error(path.string(), ":", line, ": ", why);
  };
  std::string line, first_row, comment;
  std::size_t line_no = 0;
  while (first_row.empty() && std::getline(in, line)) {
    ++line_no;
    std::string t = trim(line);
    if (line_no == 1 && t.starts_with("\xEF\xBB\xBF")) t = trim(t.substr(3));  // Excel's BOM
    if (!t.empty() && t[0] == '#') comment = trim(std::string_view(t).substr(1));
    if (!t.empty() && t[0] != '#') first_row = t;
  }
  if (first_row.empty()) throw fail(line_no, "no header row (the first row must name the columns)");
  const char sep = separator_of(first_row);
  const bool closed = sep != kWhiteSpace && first_row.back() == sep;
  std::vector<std::string> header;
  for (const std::string& f : fields_of(first_row, sep, closed)) header.push_back(field_text(f));
  double probe = 0;
  // The first row is data where it holds numbers; the comment line before it names its columns
  // if it has as many names, else the columns are x, y, z and column4... as in .xyz files.
  std::string pending, chosen;
  if (!header[0].empty() && parse_number(header[0], probe)) {
    std::vector<std::string> names = fields_of(comment, sep);
    if (names.size() != header.size() || parse_number(names[0], probe)) {
      if (header.size() < 3)
        throw fail(line_no, "the first row holds " + std::to_string(header.size()) +
                                " numbers and no header row names them: x,y,z are needed");
      names = {"x", "y", "z"};
      for (std::size_t c = 3; c < header.size(); ++c)
        names.push_back("column" + std::to_string(c + 1));
      chosen = "columns 1 to 3 as x, y, z (no header row names them)";
      if (header.size() > 3) chosen += ", the others as column4..";
    }
    pending = first_row;
    header.clear();
    for (const std::string& f : names) header.push_back(field_text(f));
  }
  for (std::size_t c = 0; c < header.size(); ++c)  // pandas' index column has no name
    header[c] = header[c].empty() ? "column" + std::to_string(c + 1) : without_unit(header[c]);

  std::vector<Column> columns;
  int position = -1;  // index into columns
  for (std::size_t i = 0; i < header.size();) {
    std::string base =
        i + 2 < header.size() ? vector_base(header[i], header[i + 1], header[i + 2]) : "";
    if (lower(header[i]) == "x" && i + 2 < header.size() && lower(header[i + 1]) == "y" &&
        lower(header[i + 2]) == "z")
      base = "position";
    if (!base.empty()) {
      if (position < 0 && is_position_base(base)) position = int(columns.size());
      columns.push_back({base, i, 3});
      i += 3;
    } else {
      columns.push_back({header[i], i, 1});
      i += 1;
    }
  }
  // x, y and z apart, in any order (a table written column by column): the position; x and y
  // alone, a 2D run's (z = 0, said). kNoColumn stands for the missing z.
  const std::size_t kNoColumn = header.size();
  std::array<std::size_t, 3> xyz{};
  if (position >= 0) {
    const std::size_t first = columns[std::size_t(position)].first;
    xyz = {first, first + 1, first + 2};
  } else {
    std::array<int, 3> found{-1, -1, -1};
    for (std::size_t c = 0; c < columns.size(); ++c)
      for (int a = 0; a < 3; ++a)
        if (columns[c].components == 1 && lower(columns[c].name) == std::string(1, char('x' + a)))
          found[std::size_t(a)] = int(c);
    if (found[0] < 0 || found[1] < 0)
      throw fail(line_no, "no position columns (x,y,z or Points:0,Points:1,Points:2; x,y for 2D)");
    for (int a = 0; a < 3; ++a)
      xyz[std::size_t(a)] =
          found[std::size_t(a)] < 0 ? kNoColumn : columns[std::size_t(found[std::size_t(a)])].first;
    if (xyz[2] == kNoColumn)
      chosen += std::string(chosen.empty() ? "" : "; ") +
                "no z column: read as a 2D run in the x-y plane (z = 0)";
  }
  // The other columns are the attributes, in their order.
  std::vector<Column> attribute_columns;
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (int(c) != position && (position >= 0 || columns[c].components != 1 ||
                               std::find(xyz.begin(), xyz.end(), columns[c].first) == xyz.end()))
      attribute_columns.push_back(columns[c]);

  ParticleData data;
  for (const Column& c : attribute_columns) data.attributes.push_back({c.name, c.components, {}});
  std::vector<double> values(header.size());
  // The rows after the header: the first row itself first where it is data.
  const auto next_row = [&](std::string& t) {
    if (!pending.empty()) {
      t = std::exchange(pending, {});
      return true;
    }
    if (!std::getline(in, line)) return false;
    ++line_no;
    t = trim(line);
    return true;
  };
  for (std::string t; next_row(t);) {
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> fields = fields_of(t, sep, closed);
    if (fields.size() != header.size())
      throw fail(line_no, std::to_string(fields.size()) + " fields; the header has " +
                              std::to_string(header.size()));
    for (std::size_t f = 0; f < fields.size(); ++f)
      if (!parse_number(fields[f], values[f]))
        throw fail(line_no, "column \"" + header[f] + "\" is not a number: \"" +
                                field_text(fields[f]) + "\"");
    data.positions.push_back(
        {values[xyz[0]], values[xyz[1]], xyz[2] == kNoColumn ? 0.0 : values[xyz[2]]});
    for (std::size_t a = 0; a < attribute_columns.size(); ++a)
      for (int k = 0; k < attribute_columns[a].components; ++k)
        data.attributes[a].values.push_back(
            float(values[attribute_columns[a].first + std::size_t(k)]));
  }
  data.chosen = chosen;
  adopt_radius_attribute(data);
  return data;
}

// One column group of extended XYZ's Properties: name, type (R real, I integer, S string, L
// logical) and its width in fields.
struct XyzProperty {
  std::string name;
  char type;
  std::size_t count;
};

// The Properties= of an extended-XYZ comment line (empty when it has none). Throws a message for
// one that does not read as name:type:count triples.
std::vector<XyzProperty> xyz_properties(const std::string& comment) {
  const std::size_t at = comment.find("Properties=");
  if (at == std::string::npos) return {};
  std::string value = comment.substr(at + 11);
  value = value.substr(0, value.find_first_of(" \t"));
  std::erase(value, '"');
  std::vector<std::string> parts;
  for (std::size_t begin = 0;;) {
    const std::size_t end = value.find(':', begin);
    parts.push_back(value.substr(begin, end - begin));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  const std::string bad = "Properties=" + value + ": not name:type:count triples";
  if (parts.size() % 3 != 0) throw std::runtime_error(bad);
  std::vector<XyzProperty> properties;
  for (std::size_t i = 0; i < parts.size(); i += 3) {
    double count = 0;
    if (parts[i].empty() || parts[i + 1].size() != 1 ||
        std::string_view("RISL").find(parts[i + 1][0]) == std::string_view::npos ||
        !parse_number(parts[i + 2], count) || count < 1 || count != std::floor(count))
      throw std::runtime_error(bad);
    properties.push_back({parts[i], parts[i + 1][0], std::size_t(count)});
  }
  return properties;
}

// The particles of an extended-XYZ file's lines [start, end) as its Properties name them.
ParticleData read_xyz_by_properties(
    const std::vector<std::string>& lines, std::size_t start,
    const std::vector<XyzProperty>& properties,
    const std::function<Error(std::size_t, const std::string&)>& fail) {
  ParticleData data;
  std::size_t fields = 0, pos = std::string::npos;
  std::vector<std::pair<std::size_t, std::size_t>> attribute_at;  // (first field, attribute)
  std::size_t radius_at = std::string::npos;
  for (const XyzProperty& p : properties) {
    const bool numeric = p.type == 'R' || p.type == 'I';
    if (p.name == "pos" && numeric && p.count == 3) pos = fields;
    else if (numeric && p.count == 1 && is_radius_name(p.name)) radius_at = fields;
    else if (numeric && (p.count == 1 || p.count == 3)) {
      attribute_at.push_back({fields, data.attributes.size()});
      data.attributes.push_back({p.name, int(p.count), {}});
    }
    fields += p.count;
  }
  if (pos == std::string::npos) throw fail(2, "Properties= names no pos:R:3 column");
  for (std::size_t l = start; l < lines.size(); ++l) {
    const std::string t = trim(lines[l]);
    if (t.empty()) continue;
    const std::vector<std::string> f = split_whitespace(t);
    if (f.size() != fields)
      throw fail(l + 1,
                 std::to_string(f.size()) + " fields; Properties= names " + std::to_string(fields));
    const auto number = [&](std::size_t c) {
      double v = 0;
      if (!parse_number(f[c], v))
        throw fail(l + 1, "field " + std::to_string(c + 1) + " is not a number: \"" + f[c] + "\"");
      return v;
    };
    data.positions.push_back({number(pos), number(pos + 1), number(pos + 2)});
    if (radius_at != std::string::npos) data.radii.push_back(float(number(radius_at)));
    for (const auto& [first, a] : attribute_at)
      for (int k = 0; k < data.attributes[a].components; ++k)
        data.attributes[a].values.push_back(float(number(first + std::size_t(k))));
  }
  data.chosen = "the columns Properties= names";
  return data;
}

ParticleData read_xyz_particles(const std::filesystem::path& path) {
  std::ifstream in = open_text(path);
  auto fail = [&](std::size_t line, const std::string& why) {
    return make_error(path.string(), ":", line, ": ", why);
  };
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::size_t start = 0;
  // Extended XYZ: "N" alone on the first line, then a comment line.
  std::vector<std::string> first =
      lines.empty() ? std::vector<std::string>{} : split_whitespace(lines[0]);
  double count = 0;
  if (first.size() == 1 && parse_number(first[0], count) && lines.size() >= 2) start = 2;
  if (start == 2) {
    std::vector<XyzProperty> properties;
    try {
      properties = xyz_properties(lines[1]);
    } catch (const std::runtime_error& e) {
      throw fail(2, e.what());
    }
    if (!properties.empty()) {
      ParticleData data = read_xyz_by_properties(lines, start, properties, fail);
      if (data.positions.size() != std::size_t(count))
        throw fail(1, "the header says " + first[0] + " particles; the file has " +
                          std::to_string(data.positions.size()));
      return data;
    }
  }

  ParticleData data;
  std::size_t columns = 0;
  for (std::size_t l = start; l < lines.size(); ++l) {
    std::string t = trim(lines[l]);
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> fields = split_whitespace(t);
    double probe = 0;
    if (!fields.empty() && !parse_number(fields[0], probe))
      fields.erase(fields.begin());  // element
    if (fields.size() < 3) throw fail(l + 1, "expected at least x y z");
    if (columns == 0) {
      columns = fields.size();
      if (columns >= 4) data.radii.reserve(lines.size());
      for (std::size_t c = 4; c < columns; ++c)
        data.attributes.push_back({"column" + std::to_string(c + 1), 1, {}});
    } else if (fields.size() != columns) {
      throw fail(l + 1, std::to_string(fields.size()) + " columns; earlier lines have " +
                            std::to_string(columns));
    }
    std::vector<double> v(columns);
    for (std::size_t c = 0; c < columns; ++c)
      if (!parse_number(fields[c], v[c]))
        throw fail(l + 1,
                   "column " + std::to_string(c + 1) + " is not a number: \"" + fields[c] + "\"");
    data.positions.push_back({v[0], v[1], v[2]});
    if (columns >= 4) data.radii.push_back(float(v[3]));
    for (std::size_t c = 4; c < columns; ++c) data.attributes[c - 4].values.push_back(float(v[c]));
  }
  if (start == 2 && data.positions.size() != std::size_t(count))
    throw fail(1, "the header says " + first[0] + " particles; the file has " +
                      std::to_string(data.positions.size()));
  return data;
}

}  // namespace voxspan
