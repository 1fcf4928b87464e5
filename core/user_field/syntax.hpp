#pragma once
// The syntax tree of a user program (program.hpp) and its parser: MATLAB's statements, operators and precedence
// (lowest first: ranges, + -, * / \ .* ./, unary + -, ^ .^ and postfix ' .', then indexing and calls).
#include <string>
#include <string_view>
#include <vector>

namespace lienewton::user_field {

enum class NodeKind {
  number,     // value
  name,       // text
  colon,      // a bare ':' index
  end,        // 'end' inside an index
  call,       // text(kids...): a function call or indexing, told apart when compiled
  binary,     // kids[0] text kids[1]; text one of + - * / \ ^ .* ./ .^
  unary,      // text kids[0]; text one of + -
  transpose,  // kids[0]'
  range,      // kids[0]:kids[1] or kids[0]:kids[1]:kids[2] (start:step:stop)
  matrix,     // [ ... ]: kids are rows, each a node of kind row
  row,        // kids are the elements of one row
  assign,     // text = kids[0]
};

struct Node {
  NodeKind kind;
  int line = 0, column = 0;
  double value = 0;
  std::string text{};
  std::vector<int> kids{};
};

struct Syntax {
  std::vector<Node> nodes;        // kids refer to nodes by index
  std::vector<int> statements;    // in order
};

// Parses a program; throws RequestError (field "g", line and column) on a syntax error or a limit.
Syntax parse(std::string_view source);

// The error every stage of the compiler throws: field g, 422, at a place in the source.
[[noreturn]] void fail_at(int line, int column, const std::string& message);

}  // namespace lienewton::user_field
