// A package's cost per pixel is a formula of its parameters, written in its
// declaration as text ("2 + samples * slices"): this is that formula, parsed
// once when the package loads (so that a bad one is an error then, naming the
// key) and evaluated for each configuration's values. Arithmetic in doubles,
// left to right, as C++ would group the same text.
//
// Grammar: numbers, names, + - * /, unary -, parentheses, and the functions
// min(a, b), max(a, b), pow(a, b), sqrt(a), floor(a), ceil(a), mod(a, b),
// slots(b) (the texture slots of a fetch of b bytes: kernels/kernel.h
// fetchSlots), the comparisons lt, le, gt, ge, eq (1 or 0) and if(c, a, b)
// (a where c is not 0, else b). Names are those the caller allows (the
// kernel's parameters, the pass's shape, named terms) and the bytes of a
// texel of each format (R16F, R32F, RG32F, RGBA8, RGBA16F, RGBA32F).
#pragma once

#include "params.h"
#include "result.h"

#include <memory>
#include <set>
#include <string>

namespace cavity::kernels {

class Expression {
public:
    // `names`: the names the formula may read besides the format constants.
    // The error says where in `text` it went wrong and what was expected.
    static Result<Expression> parse(const std::string& text, const std::set<std::string>& names);
    double evaluate(const ParamValues& values) const;
    const std::string& text() const { return text_; }
    // The names it reads (not the format constants' values: their names too).
    std::set<std::string> names() const;

    struct Node;

private:
    std::string text_;
    std::shared_ptr<const Node> root_;
};

}  // namespace cavity::kernels
