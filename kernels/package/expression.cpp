#include "package/expression.h"

#include "backend.h"
#include "kernel.h"

#include <cctype>
#include <cmath>
#include <map>
#include <vector>

namespace cavity::kernels {

struct Expression::Node {
    enum Kind { Number, Name, Unary, Binary, Call } kind = Number;
    double value = 0;
    std::string name;   // Name, Call; the operator for Unary and Binary
    std::vector<std::shared_ptr<const Node>> args;
};

namespace {

using NodePtr = std::shared_ptr<const Expression::Node>;
using Node = Expression::Node;

const std::map<std::string, double>& formatBytes() {
    static const std::map<std::string, double> bytes = {
        {"R16F", gpu::bytesPerPixel(gpu::Format::R16F)},       {"R32F", gpu::bytesPerPixel(gpu::Format::R32F)},
        {"RG32F", gpu::bytesPerPixel(gpu::Format::RG32F)},     {"RGBA8", gpu::bytesPerPixel(gpu::Format::RGBA8)},
        {"RGBA16F", gpu::bytesPerPixel(gpu::Format::RGBA16F)}, {"RGBA32F", gpu::bytesPerPixel(gpu::Format::RGBA32F)},
    };
    return bytes;
}

const std::map<std::string, int>& functionArity() {
    static const std::map<std::string, int> arity = {
        {"min", 2},   {"max", 2},  {"pow", 2}, {"sqrt", 1}, {"floor", 1}, {"ceil", 1}, {"slots", 1}, {"mod", 2},
        {"if", 3},    {"lt", 2},   {"le", 2},  {"gt", 2},   {"ge", 2},    {"eq", 2}};
    return arity;
}

// A recursive-descent parser over the text; every error names the column.
class Parser {
public:
    Parser(const std::string& text, const std::set<std::string>& names) : t_(text), names_(names) {}

    Result<NodePtr> whole() {
        CAVITY_ASSIGN(NodePtr n, sum());
        skip();
        if (i_ != t_.size()) return fail("unexpected '" + t_.substr(i_, 1) + "'");
        return n;
    }

private:
    const std::string& t_;
    const std::set<std::string>& names_;
    size_t i_ = 0;
    // Bounds that keep parsing, evaluating and freeing the tree off the end
    // of the stack: a formula is a few terms, not a program.
    static constexpr int kMaxDepth = 64;
    static constexpr int kMaxNodes = 2000;
    int depth_ = 0, nodes_ = 0;

    // Entered where the grammar nests: '(' , a call's arguments, unary minus.
    struct Nest {
        int& d;
        explicit Nest(int& depth) : d(++depth) {}
        ~Nest() { --d; }
    };
    Status room() {
        if (depth_ > kMaxDepth) return fail("nested more than " + std::to_string(kMaxDepth) + " deep");
        if (++nodes_ > kMaxNodes) return fail("more than " + std::to_string(kMaxNodes) + " terms");
        return {};
    }

    Error fail(const std::string& what) const {
        return badInput("column " + std::to_string(i_ + 1) + ": " + what);
    }
    void skip() {
        while (i_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[i_]))) ++i_;
    }
    bool eat(char c) {
        skip();
        if (i_ < t_.size() && t_[i_] == c) { ++i_; return true; }
        return false;
    }
    static NodePtr binary(char op, NodePtr a, NodePtr b) {
        auto n = std::make_shared<Node>();
        n->kind = Node::Binary;
        n->name = std::string(1, op);
        n->args = {std::move(a), std::move(b)};
        return n;
    }
    Result<NodePtr> sum() {
        CAVITY_ASSIGN(NodePtr left, product());
        for (;;) {
            if (eat('+')) { CAVITY_ASSIGN(NodePtr r, product()); left = binary('+', left, r); }
            else if (eat('-')) { CAVITY_ASSIGN(NodePtr r, product()); left = binary('-', left, r); }
            else return left;
        }
    }
    Result<NodePtr> product() {
        CAVITY_ASSIGN(NodePtr left, unary());
        for (;;) {
            if (eat('*')) { CAVITY_ASSIGN(NodePtr r, unary()); left = binary('*', left, r); }
            else if (eat('/')) { CAVITY_ASSIGN(NodePtr r, unary()); left = binary('/', left, r); }
            else return left;
        }
    }
    Result<NodePtr> unary() {
        const Nest nest(depth_);
        CAVITY_TRY(room());
        if (eat('-')) {
            CAVITY_ASSIGN(NodePtr operand, unary());
            auto n = std::make_shared<Node>();
            n->kind = Node::Unary;
            n->name = std::string(1, '-');
            n->args = {operand};
            return NodePtr(n);
        }
        return primary();
    }
    Result<NodePtr> number() {
        size_t used = 0;
        double v = 0;
        try {
            v = std::stod(t_.substr(i_), &used);
        } catch (const std::exception&) {
            return fail("a number was expected");
        }
        i_ += used;
        auto n = std::make_shared<Node>();
        n->value = v;
        return NodePtr(n);
    }
    Result<NodePtr> call(const std::string& name, int arity) {
        auto n = std::make_shared<Node>();
        n->kind = Node::Call;
        n->name = name;
        for (int a = 0; a < arity; ++a) {
            if (a > 0 && !eat(',')) return fail(name + "() takes " + std::to_string(arity) + " arguments");
            CAVITY_ASSIGN(NodePtr arg, sum());
            n->args.push_back(arg);
        }
        if (!eat(')')) return fail("')' was expected after the arguments of " + name + "()");
        return NodePtr(n);
    }
    Result<NodePtr> primary() {
        skip();
        if (i_ >= t_.size()) return fail("the formula ends where a value was expected");
        if (eat('(')) {
            CAVITY_ASSIGN(NodePtr inner, sum());
            if (!eat(')')) return fail("')' was expected");
            return inner;
        }
        const char c = t_[i_];
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
        if (!std::isalpha(static_cast<unsigned char>(c)) && c != '_') return fail("unexpected '" + std::string(1, c) + "'");
        const size_t start = i_;
        while (i_ < t_.size() && (std::isalnum(static_cast<unsigned char>(t_[i_])) || t_[i_] == '_')) ++i_;
        const std::string name = t_.substr(start, i_ - start);
        if (eat('(')) {
            const auto f = functionArity().find(name);
            if (f == functionArity().end())
                return fail("no function '" + name + "' (min, max, pow, sqrt, floor, ceil, mod, slots, if, lt, le, gt, "
                            "ge, eq)");
            return call(name, f->second);
        }
        if (!names_.count(name) && !formatBytes().count(name))
            return fail("'" + name + "' is neither a parameter of this kernel nor a format (R16F, R32F, RG32F, RGBA8, "
                        "RGBA16F, RGBA32F)");
        auto n = std::make_shared<Node>();
        n->kind = Node::Name;
        n->name = name;
        return NodePtr(n);
    }
};

double applyFunction(const std::string& f, const std::vector<double>& a) {
    if (f == "min") return std::min(a[0], a[1]);
    if (f == "max") return std::max(a[0], a[1]);
    if (f == "pow") return std::pow(a[0], a[1]);
    if (f == "sqrt") return std::sqrt(a[0]);
    if (f == "floor") return std::floor(a[0]);
    if (f == "ceil") return std::ceil(a[0]);
    if (f == "mod") return std::fmod(a[0], a[1]);
    if (f == "if") return a[0] != 0 ? a[1] : a[2];
    if (f == "lt") return a[0] < a[1];
    if (f == "le") return a[0] <= a[1];
    if (f == "gt") return a[0] > a[1];
    if (f == "ge") return a[0] >= a[1];
    if (f == "eq") return a[0] == a[1];
    return fetchSlots(a[0]);   // slots
}

double eval(const Node& n, const ParamValues& values) {
    switch (n.kind) {
    case Node::Number: return n.value;
    case Node::Name: {
        if (const auto v = values.find(n.name); v != values.end()) return v->second;
        return formatBytes().at(n.name);
    }
    case Node::Unary: return -eval(*n.args[0], values);
    case Node::Binary: {
        const double a = eval(*n.args[0], values), b = eval(*n.args[1], values);
        switch (n.name[0]) {
        case '+': return a + b;
        case '-': return a - b;
        case '*': return a * b;
        default: return a / b;
        }
    }
    case Node::Call: {
        std::vector<double> a;
        for (const auto& arg : n.args) a.push_back(eval(*arg, values));
        return applyFunction(n.name, a);
    }
    }
    return 0;
}

}  // namespace

Result<Expression> Expression::parse(const std::string& text, const std::set<std::string>& names) {
    Parser p(text, names);
    CAVITY_ASSIGN(NodePtr root, p.whole());
    Expression e;
    e.text_ = text;
    e.root_ = std::move(root);
    return e;
}

double Expression::evaluate(const ParamValues& values) const { return root_ ? eval(*root_, values) : 0; }

namespace {
void collectNames(const Node& n, std::set<std::string>& out) {
    if (n.kind == Node::Name) out.insert(n.name);
    for (const auto& a : n.args) collectNames(*a, out);
}
}  // namespace

std::set<std::string> Expression::names() const {
    std::set<std::string> out;
    if (root_) collectNames(*root_, out);
    return out;
}

}  // namespace cavity::kernels
