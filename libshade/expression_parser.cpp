#include "libshade/expression_parser.h"

namespace rs {

void FailAt(const SourceLocation& where, std::string_view usage, const std::string& message) {
    if (usage.empty())
        Report(Severity::Abort, where, "%s", message.c_str());
    else
        Report(Severity::Abort, where, "%s (usage: %.*s)", message.c_str(),
               static_cast<int>(usage.size()), usage.data());
    throw FatalError(Severity::Abort, message);  // not reached: Report throws for Abort
}

namespace {

class ExpressionParser {
  public:
    ExpressionParser(TokenStream& tokens, const SymbolTable& symbols, std::string_view usage)
        : tokens_(tokens), symbols_(symbols), usage_(usage) {}

    ExprPtr Top() {
        if (double v; ReadLiteral(tokens_, v)) return Expr::Number(v);
        const Token& t = tokens_.Peek();
        if (t.IsChar('(')) {
            tokens_.Next();
            ExprPtr e = Sum();
            Expect(')');
            return e;
        }
        Fail(t, "Expected a number or '(', found " + t.Describe());
    }

  private:
    [[noreturn]] void Fail(const Token& at, const std::string& message) {
        FailAt(at.Location(), usage_, message);
    }

    void Expect(char c) {
        const Token& t = tokens_.Peek();
        if (!t.IsChar(c))
            Fail(t, std::string("Expected '") + c + "' in expression, found " + t.Describe());
        tokens_.Next();
    }

    // Guards recursion on '(' and unary operators.
    struct Nest {
        explicit Nest(ExpressionParser& p) : parser(p) {
            if (++parser.nesting_ > kMaxExprNesting)
                parser.Fail(parser.tokens_.Peek(), "Expression nested too deeply");
        }
        ~Nest() { --parser.nesting_; }
        ExpressionParser& parser;
    };

    ExprPtr Checked(ExprPtr e, const Token& at) {
        if (e->Depth() > kMaxExprDepth || e->Cost() > kMaxExprCost)
            Fail(at, "Expression too complex");
        return e;
    }

    ExprPtr Sum() {
        ExprPtr left = Product();
        while (true) {
            const Token& t = tokens_.Peek();
            if (!t.IsChar('+') && !t.IsChar('-')) return left;
            Token op = tokens_.Next();
            ExprPtr right = Product();
            left = Checked(
                Expr::Binary(op.IsChar('+') ? Expr::Op::Add : Expr::Op::Subtract, left, right), op);
        }
    }

    ExprPtr Product() {
        ExprPtr left = Unary();
        while (true) {
            const Token& t = tokens_.Peek();
            Expr::Op op;
            if (t.IsChar('*'))
                op = Expr::Op::Multiply;
            else if (t.IsChar('/'))
                op = Expr::Op::Divide;
            else if (t.IsChar('%'))
                op = Expr::Op::Modulo;
            else
                return left;
            Token opTok = tokens_.Next();
            ExprPtr right = Unary();
            left = Checked(Expr::Binary(op, left, right), opTok);
        }
    }

    // Unary signs bind more loosely than '^': -2^2 = -(2^2).
    ExprPtr Unary() {
        const Token& t = tokens_.Peek();
        if (t.IsChar('-') || t.IsChar('+')) {
            Nest guard(*this);
            bool negative = tokens_.Next().IsChar('-');
            ExprPtr operand = Unary();
            return negative ? Expr::Negate(operand) : operand;
        }
        return Power();
    }

    // Right associative; the exponent may carry a sign: 2^-1 = 0.5, 2^3^0 = 2.
    ExprPtr Power() {
        ExprPtr base = Primary();
        const Token& t = tokens_.Peek();
        if (!t.IsChar('^')) return base;
        Token op = tokens_.Next();
        Nest guard(*this);
        ExprPtr exponent = Unary();
        return Checked(Expr::Binary(Expr::Op::Power, base, exponent), op);
    }

    ExprPtr Primary() {
        const Token& t = tokens_.Peek();
        if (t.kind == TokenKind::Number) return Expr::Number(tokens_.Next().number);
        if (t.IsChar('(')) {
            Nest guard(*this);
            tokens_.Next();
            ExprPtr e = Sum();
            Expect(')');
            return e;
        }
        if (t.kind == TokenKind::Name) return NameOrCall();
        Fail(t, "Unexpected " + t.Describe() + " in expression");
    }

    ExprPtr NameOrCall() {
        Token name = tokens_.Next();
        const std::string spelling(name.text);
        const Symbol* s = symbols_.Find(spelling);
        bool call = tokens_.Peek().IsChar('(');
        if (!s)
            Fail(name, "Undefined " + std::string(call ? "function" : "variable") + " '" +
                           spelling + "'");
        if (!call) {
            if (s->kind == Symbol::Kind::Function)
                Fail(name, "'" + spelling + "' is a function; it needs arguments");
            return s->value;
        }
        if (s->kind != Symbol::Kind::Function) Fail(name, "'" + spelling + "' is not a function");
        Nest guard(*this);
        tokens_.Next();  // '('
        std::vector<ExprPtr> args{Sum()};
        while (tokens_.Peek().IsChar(',')) {
            tokens_.Next();
            args.push_back(Sum());
        }
        Expect(')');
        if (static_cast<int>(args.size()) != s->arity) {
            Fail(name, StringPrintf("Function '%s' takes %d argument%s, not %zu", spelling.c_str(),
                                    s->arity, s->arity == 1 ? "" : "s", args.size()));
        }
        ExprPtr e;
        if (s->isLinear)
            e = Expr::Linear(args[0], args[1], args[2], args[3]);
        else if (s->arity == 1)
            e = Expr::Call(s->fn1, args[0]);
        else
            e = Expr::Call(s->fn2, args[0], args[1]);
        return Checked(e, name);
    }

    TokenStream& tokens_;
    const SymbolTable& symbols_;
    std::string_view usage_;
    int nesting_ = 0;
};

}  // namespace

bool ReadLiteral(TokenStream& tokens, double& value) {
    if (Lexer* lexer = tokens.DirectLexer()) return lexer->NextLiteral(value);
    const Token& t = tokens.Peek();
    if (t.kind == TokenKind::Number) {
        value = t.number;
        tokens.Skip();
        return true;
    }
    if ((t.IsChar('-') || t.IsChar('+')) && tokens.Peek(1).kind == TokenKind::Number) {
        const bool negative = tokens.Peek().IsChar('-');
        const double v = tokens.Peek(1).number;
        tokens.Skip();
        tokens.Skip();
        value = negative ? -v : v;
        return true;
    }
    return false;
}

bool PeekExpression(TokenStream& tokens) {
    if (Lexer* lexer = tokens.DirectLexer()) return lexer->StartsExpression();
    const Token& t = tokens.Peek();
    if (t.kind == TokenKind::Number || t.IsChar('(')) return true;
    return (t.IsChar('-') || t.IsChar('+')) && tokens.Peek(1).kind == TokenKind::Number;
}

ExprPtr ParseExpression(TokenStream& tokens, const SymbolTable& symbols, std::string_view usage) {
    return ExpressionParser(tokens, symbols, usage).Top();
}

}  // namespace rs
