// assimp_extensions.cpp — prints the file extensions the linked assimp
// imports, one a line, lower case, without the dot. The corpus test
// (assimp_corpus.py) renders every file of the test models with one of them.
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>
#include <string>

int main()
{
  std::string list;
  Assimp::Importer().GetExtensionList(list);  // "*.3ds;*.obj;..."
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ';');) {
    if (item.rfind("*.", 0) == 0) item = item.substr(2);
    std::transform(item.begin(), item.end(), item.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (!item.empty()) std::printf("%s\n", item.c_str());
  }
  return 0;
}
