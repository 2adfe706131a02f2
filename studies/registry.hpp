#pragma once
// Where each built-in study is defined: the file `nsbench-study list` names beside it (its C++
// source while it is written in C++; its study file once it is one, issue 31).
#include <string>

namespace nsb {

// The file that defines the built-in study `name`, relative to the repository; "" for a name
// that is no built-in study.
std::string study_source(const std::string& name);

}  // namespace nsb
