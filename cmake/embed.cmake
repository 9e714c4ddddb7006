# Writes OUT: a C++ table of the text files listed in FILES ("|"-separated,
# under ROOT), returned by NAMESPACE::FUNCTION() as a map from each file's
# path under ROOT to its text. The kernels' GLSL (kernels/) and the gate
# report's page (harness/report/) travel inside the binaries this way.
string(REPLACE "|" ";" FILES "${FILES}")
set(body "#include <map>\n#include <string>\nnamespace ${NAMESPACE} {\nconst std::map<std::string, std::string>& ${FUNCTION}() {\n  static const std::map<std::string, std::string> files = {\n")
foreach(f ${FILES})
  file(READ ${ROOT}/${f} text)
  # Raw strings cannot hold their own delimiter; the embedded files never contain it.
  string(APPEND body "    {\"${f}\", R\"cavity_src(${text})cavity_src\"},\n")
endforeach()
string(APPEND body "  };\n  return files;\n}\n}  // namespace ${NAMESPACE}\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
