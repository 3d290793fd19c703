#include <fstream>
#include <iterator>
#include <cstdio>
#include "fuzz_cases.h"
int main(int argc, char** argv) {
    std::ifstream f(argv[2], std::ios::binary);
    std::string s((std::istreambuf_iterator<char>(f)), {});
    std::string what = argv[1];
    std::string p = what == "png" ? rt_fuzz::png_case(s) : what == "merge" ? rt_fuzz::merge_case(s) : rt_fuzz::checkpoint_case(s);
    printf("problem: %s\n", p.c_str());
}
