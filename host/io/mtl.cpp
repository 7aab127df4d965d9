// mtl.cpp — the plain MTL reader (see mtl.h). Lines are dispatched as
// ObjFileMtlImporter::load dispatches them: on their first character once
// leading blanks are skipped (assimp skips them on every line but the first).
#include "io/mtl.h"

#include <assimp/fast_atof.h>

#include <cstring>
#include <strings.h>
#include <set>

namespace clr {

namespace {

bool isBlank(char c)
{
  return c == ' ' || c == '\t';
}

// The words of [b, e), split at blanks.
std::vector<std::pair<const char*, const char*>> words(const char* b, const char* e)
{
  std::vector<std::pair<const char*, const char*>> out;
  while (b < e) {
    while (b < e && isBlank(*b)) ++b;
    const char* start = b;
    while (b < e && !isBlank(*b)) ++b;
    if (b > start) out.emplace_back(start, b);
  }
  return out;
}

// The words after the first are `count` numbers.
bool numbers(const std::vector<std::pair<const char*, const char*>>& w, size_t count, float* values)
{
  if (w.size() != count + 1) return false;
  for (size_t k = 0; k < count; ++k)
    if (!assimpNumber(w[k + 1].first, w[k + 1].second, values[k])) return false;
  return true;
}

// The rest of the line after its first word, as assimp's getName and
// createMaterial take it; "" when empty, or when it has a character that
// could make the two readers differ.
std::string rest(const char* b, const char* e)
{
  while (b < e && !isBlank(*b)) ++b;
  while (b < e && isBlank(*b)) ++b;
  if (b == e || e - b > 500) return "";
  for (const char* p = b; p < e; ++p)
    if (static_cast<unsigned char>(*p) < 0x20 && *p != '\t') return "";
  return std::string(b, e);
}

// What fast_atof throws for a word it cannot read (plainDecimal lets none through).
struct NotANumber {
  template <typename... Parts>
  explicit NotANumber(Parts&&...)
  {
  }
};

}  // namespace

bool plainDecimal(const char* b, const char* e)
{
  const char* p = b;
  if (p < e && (*p == '+' || *p == '-')) ++p;
  const char* digits = p;
  while (p < e && *p >= '0' && *p <= '9') ++p;
  if (p == digits || p - digits > 18) return false;
  if (p < e && *p == '.') {
    const char* fraction = ++p;
    while (p < e && *p >= '0' && *p <= '9') ++p;
    if (p == fraction || p - fraction > 40) return false;
  }
  if (p < e && (*p == 'e' || *p == 'E')) {
    ++p;
    if (p < e && (*p == '+' || *p == '-')) ++p;
    const char* exponent = p;
    while (p < e && *p >= '0' && *p <= '9') ++p;
    if (p == exponent || p - exponent > 3) return false;
  }
  return p == e;
}

bool assimpNumber(const char* b, const char* e, float& value)
{
  if (!plainDecimal(b, e)) return false;
  ai_real v = 0;
  try {
    if (Assimp::fast_atoreal_move<ai_real, NotANumber>(b, v, true) != e) return false;
  } catch (const NotANumber&) {
    return false;
  }
  value = float(v);
  return true;
}

bool readPlainMtl(const std::string& text, std::vector<MtlMaterial>& out)
{
  // What assimp's text reader would convert (a byte-order mark, UTF-16) or
  // skip (a first line that starts with a blank).
  if (!text.empty()) {
    const unsigned char first = static_cast<unsigned char>(text[0]);
    if (first == 0xEF || first == 0xFE || first == 0xFF || first == 0 || isBlank(text[0])) return false;
  }
  std::set<std::string> names;
  const size_t before = out.size();  // `current` names out[out.size() - 1] once past it
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p < end) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    const char* e = nl ? nl : end;
    const char* b = p;
    p = nl ? nl + 1 : end;
    if (e > b && e[-1] == '\r') --e;
    for (const char* q = b; q < e; ++q)
      if (*q == '\r' || *q == '\0' || *q == '\f') return false;
    while (b < e && isBlank(*b)) ++b;
    if (b == e) continue;
    const auto w = words(b, e);
    const std::string first(w[0].first, w[0].second);
    MtlMaterial* current = out.size() > before ? &out.back() : nullptr;
    float v[3];
    switch (*b) {
      case 'k':
      case 'K':
        if (first != "Ka" && first != "Kd" && first != "Ks" && first != "Ke") return false;
        if (!current || !numbers(w, 3, v)) return false;
        if (first == "Kd") std::copy(v, v + 3, current->diffuse);
        break;
      case 'T':
        if (!current || !(first == "Tf" ? numbers(w, 3, v) : first == "Tr" && numbers(w, 1, v))) return false;
        break;
      case 'd':
        if (first == "d") {
          if (!current || !numbers(w, 1, v)) return false;
          break;
        }
        if (first != "disp" || !current || rest(b, e).empty() || *w[1].first == '-') return false;
        break;
      case 'N':
      case 'n':
        if (first == "newmtl") {
          std::string name = rest(b, e);
          while (!name.empty() && isBlank(name.back())) name.pop_back();
          if (name.empty() || !names.insert(name).second) return false;
          out.push_back(MtlMaterial{});
          out.back().name = name;
          break;
        }
        if (first == "norm") {
          if (!current || rest(b, e).empty() || *w[1].first == '-') return false;
          break;
        }
        if ((first != "Ns" && first != "Ni") || !current || !numbers(w, 1, v)) return false;
        break;
      case 'm':
      case 'b':
      case 'r': {
        // assimp reads any texture statement's options (-bm, -clamp) and name; the scene uses map_Kd's.
        if (!current || w.size() < 2 || *w[1].first == '-') return false;
        if (strncasecmp(b, "map_kd", 6) != 0) break;
        // Trailing blanks stay in assimp's texture name: not plain.
        const std::string name = rest(b, e);
        if (first != "map_Kd" || name.empty() || isBlank(e[-1])) return false;
        current->texture = name;
        break;
      }
      case 'i':
        if (first != "illum") return false;
        break;
      case 'P':
      case 'a': return false;
      default:  // assimp skips the line ('#' comments among them)
        break;
    }
  }
  return true;
}

bool mtlReadableByAssimp(const std::string& text)
{
  // Lines as ObjFileMtlImporter::load dispatches them: by their first character after leading blanks.
  for (size_t p = 0; p < text.size();) {
    size_t e = p;
    while (e < text.size() && text[e] != '\n' && text[e] != '\r' && text[e] != '\f' && text[e] != '\0') ++e;
    size_t b = p;
    while (b < e && isBlank(text[b])) ++b;
    p = e + 1;
    if (b == e) continue;
    const char c = text[b], next = b + 1 < e ? text[b + 1] : '\0';
    if ((c == 'n' || c == 'N') && next == 'e') return true;  // newmtl: a material from here on
    if (c == 'm' || c == 'b' || c == 'r' || c == 'a' || ((c == 'n' || c == 'N') && next == 'o') ||
        text.compare(b, 4, "disp") == 0)
      return false;
  }
  return true;
}

}  // namespace clr
