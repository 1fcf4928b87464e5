#include "syntax.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "../request_error.hpp"
#include "program.hpp"

namespace lienewton::user_field {

void fail_at(int line, int column, const std::string& message) {
  throw RequestError(RequestError::Kind::unprocessable, "g", message, line, column);
}

namespace {

enum class Tok { number, name, op, open_paren, close_paren, open_bracket, close_bracket, comma, semicolon, newline, eof };

struct Token {
  Tok kind;
  std::string text;
  double value = 0;
  int line = 1, column = 1;
};

bool ends_value(const Token& t) {
  return t.kind == Tok::number || t.kind == Tok::name || t.kind == Tok::close_paren ||
         t.kind == Tok::close_bracket || (t.kind == Tok::op && (t.text == "'" || t.text == ".'"));
}

// MATLAB's lexical rules, including the one inside [ ]: whitespace between two values separates elements
// ([1 -2] has two, [1 - 2] one).
class Lexer {
 public:
  explicit Lexer(std::string_view s) : s_(s) {}

  std::vector<Token> run() {
    std::vector<Token> out;
    while (true) {
      const bool spaced = skip_blanks();
      if (i_ >= s_.size()) break;
      const char c = s_[i_];
      if (!open_.empty() && open_.back().bracket == '[' && spaced && !out.empty() && ends_value(out.back()) &&
          starts_element()) {
        out.push_back(Token{Tok::comma, ",", 0, line_, col_});
      }
      if (c == '\n') {
        if (!open_.empty() && open_.back().bracket == '[') out.push_back(Token{Tok::semicolon, ";", 0, line_, col_});
        else if (open_.empty()) out.push_back(Token{Tok::newline, "\n", 0, line_, col_});
        advance();
        continue;
      }
      out.push_back(next(c, out));
    }
    // At the bracket left open, not at the end: a missing ')' on line 1 otherwise points past the last line.
    if (!open_.empty())
      fail_at(open_.back().line, open_.back().column,
              std::string("this '") + open_.back().bracket + "' is never closed (the program ends first)");
    out.push_back(Token{Tok::eof, "", 0, line_, col_});
    return out;
  }

 private:
  void advance() {
    if (s_[i_] == '\n') {
      ++line_;
      col_ = 1;
    } else {
      ++col_;
    }
    ++i_;
  }
  char peek(std::size_t k = 1) const { return i_ + k < s_.size() ? s_[i_ + k] : '\0'; }

  // Skips spaces, tabs, comments (% or # to the end of the line) and continuations (... to the end of the
  // line); returns whether anything was skipped.
  bool skip_blanks() {
    bool skipped = false;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == ' ' || c == '\t' || c == '\r' || (c == '\n' && !open_.empty() && open_.back().bracket == '(')) {
        advance();
      } else if (c == '%' || c == '#') {
        while (i_ < s_.size() && s_[i_] != '\n') advance();
      } else if (c == '.' && peek() == '.' && peek(2) == '.') {
        while (i_ < s_.size() && s_[i_] != '\n') advance();
        if (i_ < s_.size()) advance();
      } else {
        break;
      }
      skipped = true;
    }
    return skipped;
  }

  // Inside [ ] after whitespace: does a new element start here?
  bool starts_element() const {
    const char c = s_[i_];
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '(' || c == '[') return true;
    if (c == '.' && std::isdigit(static_cast<unsigned char>(peek()))) return true;
    if ((c == '+' || c == '-') && peek() != ' ' && peek() != '\t' && peek() != '=') return true;
    return false;
  }

  Token next(char c, const std::vector<Token>& before) {
    Token t{Tok::op, "", 0, line_, col_};
    if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && std::isdigit(static_cast<unsigned char>(peek())))) {
      const std::size_t start = i_;
      while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) advance();
      if (i_ < s_.size() && s_[i_] == '.' && !(peek() == '*' || peek() == '/' || peek() == '^' || peek() == '\'')) {
        advance();
        while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) advance();
      }
      if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
        const char sign = peek();
        const std::size_t digit = (sign == '+' || sign == '-') ? 2 : 1;
        if (std::isdigit(static_cast<unsigned char>(peek(digit)))) {
          for (std::size_t k = 0; k < digit; ++k) advance();
          while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) advance();
        }
      }
      const std::string text(s_.substr(start, i_ - start));
      t.kind = Tok::number;
      t.text = text;
      t.value = std::strtod(text.c_str(), nullptr);
      if (!std::isfinite(t.value)) fail_at(t.line, t.column, "the number " + text + " is too large for a double");
      if (i_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_'))
        fail_at(line_, col_, "unexpected '" + std::string(1, s_[i_]) + "' after the number " + text +
                                 " (write 2*y, not 2y)");
      return t;
    }
    if (std::isalpha(static_cast<unsigned char>(c))) {
      const std::size_t start = i_;
      while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_')) advance();
      t.kind = Tok::name;
      t.text = std::string(s_.substr(start, i_ - start));
      return t;
    }
    auto one = [&](Tok kind) {
      t.kind = kind;
      t.text = std::string(1, c);
      advance();
      return t;
    };
    switch (c) {
      case '(': open_.push_back({'(', line_, col_}); return one(Tok::open_paren);
      case '[': open_.push_back({'[', line_, col_}); return one(Tok::open_bracket);
      case ')':
      case ']': {
        const char want = c == ')' ? '(' : '[';
        if (open_.empty() || open_.back().bracket != want)
          fail_at(line_, col_, std::string("unbalanced '") + c + "'");
        open_.pop_back();
        return one(c == ')' ? Tok::close_paren : Tok::close_bracket);
      }
      case ',': return one(Tok::comma);
      case ';': return one(Tok::semicolon);
      case '\'':
        if (before.empty() || !ends_value(before.back()) ||
            (!open_.empty() && open_.back().bracket == '[' && i_ > 0 && (s_[i_ - 1] == ' ' || s_[i_ - 1] == '\t')))
          fail_at(line_, col_, "strings are not supported ('  is the transpose, after a value)");
        return one(Tok::op);
      case '.':
        if (peek() == '*' || peek() == '/' || peek() == '^' || peek() == '\'') {
          t.text = std::string(1, c) + peek();
          advance();
          advance();
          return t;
        }
        break;
      case '+': case '-': case '*': case '/': case '\\': case '^': case ':': return one(Tok::op);
      case '=':
        if (peek() == '=') fail_at(line_, col_, "comparisons (==) are not supported");
        return one(Tok::op);
      default: break;
    }
    const unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) fail_at(line_, col_, std::string("unexpected character '") + c + "'");
    fail_at(line_, col_, "unexpected character (byte " + std::to_string(u) + "): programs are plain ASCII");
  }

  std::string_view s_;
  std::size_t i_ = 0;
  int line_ = 1, col_ = 1;
  struct Open {
    char bracket;
    int line, column;
  };
  std::vector<Open> open_;  // the brackets open here, innermost last
};

class Parser {
 public:
  explicit Parser(std::vector<Token> toks) : t_(std::move(toks)) {}

  Syntax run() {
    while (true) {
      while (at(Tok::semicolon) || at(Tok::comma) || at(Tok::newline)) ++p_;
      if (at(Tok::eof)) break;
      out_.statements.push_back(statement());
      if (!(at(Tok::semicolon) || at(Tok::comma) || at(Tok::newline) || at(Tok::eof)))
        fail_at(cur().line, cur().column, "unexpected " + describe(cur()) + ": expected ';' or a new line");
    }
    return std::move(out_);
  }

 private:
  const Token& cur() const { return t_[p_]; }
  bool at(Tok k) const { return cur().kind == k; }
  bool at_op(std::string_view s) const { return cur().kind == Tok::op && cur().text == s; }
  static std::string describe(const Token& t) {
    if (t.kind == Tok::eof) return "end of program";
    if (t.kind == Tok::newline) return "end of line";
    return "'" + t.text + "'";
  }

  int add(Node n) {
    if (out_.nodes.size() >= static_cast<std::size_t>(kMaxNodes))
      fail_at(n.line, n.column, "the program is too long: more than " + std::to_string(kMaxNodes) + " terms");
    out_.nodes.push_back(std::move(n));
    return static_cast<int>(out_.nodes.size()) - 1;
  }
  int make(NodeKind kind, const Token& at, std::string text, std::vector<int> kids) {
    Node n{kind, at.line, at.column};
    n.text = std::move(text);
    n.kids = std::move(kids);
    return add(std::move(n));
  }

  struct Deeper {
    explicit Deeper(Parser& p) : p_(p) {
      if (++p_.depth_ > kMaxNesting)
        fail_at(p_.cur().line, p_.cur().column,
                "the program nests too deeply (more than " + std::to_string(kMaxNesting) + " levels)");
    }
    ~Deeper() { --p_.depth_; }
    Parser& p_;
  };

  int statement() {
    if (at(Tok::name) && t_[p_ + 1].kind == Tok::op && t_[p_ + 1].text == "=") {
      const Token& name = cur();
      p_ += 2;
      return make(NodeKind::assign, name, name.text, {expression()});
    }
    const int e = expression();
    if (at_op("=")) fail_at(cur().line, cur().column, "only a plain name can be assigned to (no indexed assignment)");
    return e;
  }

  void expect(Tok k, const char* what) {
    if (!at(k)) fail_at(cur().line, cur().column, "unexpected " + describe(cur()) + ": expected " + what);
    ++p_;
  }

  int expression() {
    Deeper d(*this);
    const int first = additive();
    if (!at_op(":")) return first;
    const Token& colon = cur();
    ++p_;
    std::vector<int> kids{first, additive()};
    if (at_op(":")) {
      ++p_;
      kids.push_back(additive());
    }
    return make(NodeKind::range, colon, ":", std::move(kids));
  }

  int additive() {
    int left = multiplicative();
    while (at_op("+") || at_op("-")) {
      const Token op = cur();
      ++p_;
      left = make(NodeKind::binary, op, op.text, {left, multiplicative()});
    }
    return left;
  }

  int multiplicative() {
    int left = unary();
    while (at_op("*") || at_op("/") || at_op("\\") || at_op(".*") || at_op("./")) {
      const Token op = cur();
      ++p_;
      left = make(NodeKind::binary, op, op.text, {left, unary()});
    }
    return left;
  }

  int unary() {
    Deeper d(*this);
    if (at_op("+") || at_op("-")) {
      const Token op = cur();
      ++p_;
      return make(NodeKind::unary, op, op.text, {unary()});
    }
    return power();
  }

  // ^ .^ ' .' are left-associative at one level (2^3^2 = 64, a^b' = (a^b)').
  int power() {
    int left = postfix();
    while (true) {
      if (at_op("'") || at_op(".'")) {
        const Token op = cur();
        ++p_;
        left = make(NodeKind::transpose, op, op.text, {left});
      } else if (at_op("^") || at_op(".^")) {
        const Token op = cur();
        ++p_;
        left = make(NodeKind::binary, op, op.text, {left, exponent()});
      } else {
        return left;
      }
    }
  }

  // MATLAB reads 2^-1 as 2^(-1).
  int exponent() {
    Deeper d(*this);
    if (at_op("+") || at_op("-")) {
      const Token op = cur();
      ++p_;
      return make(NodeKind::unary, op, op.text, {exponent()});
    }
    return postfix();
  }

  int postfix() {
    const Token first = cur();
    const int p = primary();
    if (first.kind != Tok::name || !at(Tok::open_paren)) return p;
    ++p_;
    std::vector<int> args;
    if (!at(Tok::close_paren)) {
      while (true) {
        if (at_op(":") && (t_[p_ + 1].kind == Tok::comma || t_[p_ + 1].kind == Tok::close_paren)) {
          args.push_back(make(NodeKind::colon, cur(), ":", {}));
          ++p_;
        } else {
          args.push_back(expression());
        }
        if (at(Tok::comma)) {
          ++p_;
          continue;
        }
        break;
      }
    }
    expect(Tok::close_paren, "')' or ','");
    if (at(Tok::open_paren)) fail_at(cur().line, cur().column, "an index cannot be indexed again: use a local name");
    return make(NodeKind::call, first, first.text, std::move(args));
  }

  int primary() {
    const Token tok = cur();
    switch (tok.kind) {
      case Tok::number: {
        ++p_;
        Node n{NodeKind::number, tok.line, tok.column, tok.value, tok.text};
        return add(std::move(n));
      }
      case Tok::name:
        ++p_;
        return make(tok.text == "end" ? NodeKind::end : NodeKind::name, tok, tok.text, {});
      case Tok::open_paren: {
        ++p_;
        const int e = expression();
        expect(Tok::close_paren, "')'");
        return e;
      }
      case Tok::open_bracket: return matrix();
      default: break;
    }
    fail_at(tok.line, tok.column, "unexpected " + describe(tok) + ": expected a value");
  }

  int matrix() {
    Deeper d(*this);
    const Token open = cur();
    ++p_;
    std::vector<int> rows;
    std::vector<int> elements;
    Token row_start = cur();
    auto end_row = [&] {
      if (!elements.empty()) rows.push_back(make(NodeKind::row, row_start, "", std::move(elements)));
      elements.clear();
    };
    while (!at(Tok::close_bracket)) {
      if (at(Tok::semicolon)) {
        ++p_;
        end_row();
        row_start = cur();
        continue;
      }
      if (at(Tok::comma)) {
        ++p_;
        continue;
      }
      if (at(Tok::eof)) fail_at(cur().line, cur().column, "the program ends before this '[' is closed");
      elements.push_back(expression());
    }
    end_row();
    ++p_;
    return make(NodeKind::matrix, open, "[]", std::move(rows));
  }

  std::vector<Token> t_;
  std::size_t p_ = 0;
  int depth_ = 0;
  Syntax out_;
};

}  // namespace

Syntax parse(std::string_view source) {
  if (source.size() > kMaxSourceBytes)
    fail_at(1, 1, "the program is too long: " + std::to_string(source.size()) + " characters, at most " +
                      std::to_string(kMaxSourceBytes));
  return Parser(Lexer(source).run()).run();
}

}  // namespace lienewton::user_field
