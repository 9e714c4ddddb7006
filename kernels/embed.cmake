# Writes OUT: a C++ table of the kernel files listed in FILES ("|"-separated, under ROOT).
string(REPLACE "|" ";" FILES "${FILES}")
set(body "#include <map>\n#include <string>\nnamespace cavity::kernels {\nconst std::map<std::string, std::string>& embeddedSources() {\n  static const std::map<std::string, std::string> files = {\n")
foreach(f ${FILES})
  file(READ ${ROOT}/${f} text)
  # Raw strings cannot hold their own delimiter; kernels never contain it.
  string(APPEND body "    {\"${f}\", R\"cavity_src(${text})cavity_src\"},\n")
endforeach()
string(APPEND body "  };\n  return files;\n}\n}  // namespace cavity::kernels\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
