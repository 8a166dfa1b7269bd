#include "harness/usda/usda_lexer.h"

#include <cstdio>

namespace obscura::usda {

namespace {

bool isIdentStart(char c) {
    // Bytes of multi-byte UTF-8 sequences are accepted so that Unicode names lex as one token.
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || static_cast<unsigned char>(c) >= 0x80;
}
bool isIdentChar(char c) { return isIdentStart(c) || (c >= '0' && c <= '9'); }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

int hexDigit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// Decodes C-style escapes as USD does (\n, \t, \\, \", \', \xHH, octal); unknown escapes keep the character.
std::string unescape(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '\\' || i + 1 == s.size()) {
            out += s[i];
            continue;
        }
        const char e = s[++i];
        switch (e) {
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        case 'r': out += '\r'; break;
        case 'a': out += '\a'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'v': out += '\v'; break;
        case 'x': {
            int value = 0;
            int digits = 0;
            while (digits < 2 && i + 1 < s.size() && hexDigit(s[i + 1]) >= 0) {
                value = value * 16 + hexDigit(s[++i]);
                ++digits;
            }
            out += digits ? static_cast<char>(value) : 'x';
            break;
        }
        default:
            if (e >= '0' && e <= '7') {
                int value = e - '0';
                for (int digits = 1; digits < 3 && i + 1 < s.size() && s[i + 1] >= '0' && s[i + 1] <= '7'; ++digits)
                    value = value * 8 + (s[++i] - '0');
                out += static_cast<char>(value);
            } else {
                out += e;
            }
        }
    }
    return out;
}

std::string printable(char c) {
    if (c >= 0x20 && c < 0x7f) return std::string("'") + c + "'";
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02x", static_cast<unsigned char>(c));
    return buf;
}

}  // namespace

std::string describe(const Token& token) {
    switch (token.kind) {
    case TokenKind::EndOfFile: return "end of file";
    case TokenKind::Newline: return "end of line";
    case TokenKind::String: return "string \"" + token.value + "\"";
    case TokenKind::Error: return token.value;
    default: return "'" + std::string(token.text) + "'";
    }
}

const Token& Lexer::peek() {
    if (!hasPeeked_) {
        peeked_ = scan();
        hasPeeked_ = true;
    }
    return peeked_;
}

Token Lexer::next() {
    if (hasPeeked_) {
        hasPeeked_ = false;
        return std::move(peeked_);
    }
    return scan();
}

Token Lexer::make(TokenKind kind, size_t begin, int line, int column) {
    Token t;
    t.kind = kind;
    t.text = src_.substr(begin, pos_ - begin);
    t.line = line;
    t.column = column;
    return t;
}

Token Lexer::error(size_t begin, int line, int column, std::string message) {
    Token t = make(TokenKind::Error, begin, line, column);
    t.value = std::move(message);
    // Stop here: everything after a lexical error would be noise.
    pos_ = src_.size();
    return t;
}

void Lexer::advanceOver(size_t count) {
    const size_t end = pos_ + count;
    while (pos_ < end) {
        const char c = src_[pos_++];
        if (c == '\n' || (c == '\r' && ch() != '\n')) {
            ++line_;
            lineStart_ = pos_;
        }
    }
}

Token Lexer::scan() {
    for (;;) {
        while (ch() == ' ' || ch() == '\t' || ch() == '\f' || ch() == '\v') ++pos_;
        if (pos_ >= src_.size()) return make(TokenKind::EndOfFile, pos_, line_, column());
        const size_t begin = pos_;
        const int line = line_;
        const int col = column();
        if (ch() == '#') {
            while (pos_ < src_.size() && ch() != '\n' && ch() != '\r') ++pos_;
            // Only the very first line carries the format cookie; other # lines are comments.
            if (begin == 0) return make(TokenKind::Magic, begin, line, col);
            continue;
        }
        if (at("//")) {
            while (pos_ < src_.size() && ch() != '\n' && ch() != '\r') ++pos_;
            continue;
        }
        if (at("/*")) {
            const size_t close = src_.find("*/", pos_ + 2);
            if (close == std::string_view::npos) return error(begin, line, col, "unterminated /* comment");
            // Like USD, a block comment swallows its newlines rather than separating statements.
            advanceOver(close + 2 - pos_);
            continue;
        }
        break;
    }
    const char c = ch();
    if (c == '\n' || c == '\r') return scanNewline();
    if (isIdentStart(c)) return scanIdentifier();
    if (isDigit(c) || (c == '.' && isDigit(ch(1))) || (c == '-' && (isDigit(ch(1)) || (ch(1) == '.' && isDigit(ch(2))) || at("-inf"))))
        return scanNumber();
    if (c == '"' || c == '\'') return scanString();
    if (c == '@') return scanAssetPath();
    if (c == '<') return scanPathRef();
    const size_t begin = pos_;
    const int col = column();
    static constexpr std::string_view kPunct = "=,:;.[](){}&";  // '&' joins a spline knot's two values
    if (kPunct.find(c) != std::string_view::npos) {
        ++pos_;
        return make(TokenKind::Punct, begin, line_, col);
    }
    ++pos_;
    return error(begin, line_, col, "unexpected character " + printable(c));
}

Token Lexer::scanNewline() {
    const size_t begin = pos_;
    const int line = line_;
    const int col = column();
    pos_ += at("\r\n") ? 2 : 1;
    ++line_;
    lineStart_ = pos_;
    return make(TokenKind::Newline, begin, line, col);
}

Token Lexer::scanIdentifier() {
    const size_t begin = pos_;
    const int col = column();
    while (isIdentChar(ch())) ++pos_;
    // Namespaced ("primvars:st") and C++-namespaced ("Foo::Bar") names are single tokens.
    for (;;) {
        if (ch() == ':' && isIdentStart(ch(1))) {
            pos_ += 1;
        } else if (at("::") && isIdentStart(ch(2))) {
            pos_ += 2;
        } else {
            break;
        }
        while (isIdentChar(ch())) ++pos_;
    }
    return make(TokenKind::Identifier, begin, line_, col);
}

Token Lexer::scanNumber() {
    const size_t begin = pos_;
    const int col = column();
    if (ch() == '-') ++pos_;
    if (at("inf")) {
        pos_ += 3;
        return make(TokenKind::Number, begin, line_, col);
    }
    while (isDigit(ch())) ++pos_;
    if (ch() == '.') {
        ++pos_;
        while (isDigit(ch())) ++pos_;
    }
    if ((ch() == 'e' || ch() == 'E') && (isDigit(ch(1)) || ((ch(1) == '+' || ch(1) == '-') && isDigit(ch(2))))) {
        pos_ += 2;
        while (isDigit(ch())) ++pos_;
    }
    return make(TokenKind::Number, begin, line_, col);
}

Token Lexer::scanString() {
    const size_t begin = pos_;
    const int line = line_;
    const int col = column();
    const char quote = ch();
    const std::string triple(3, quote);
    if (at(triple)) {
        // Triple-quoted strings may span lines; a backslash escapes the next character.
        size_t i = pos_ + 3;
        while (i < src_.size() && src_.substr(i, 3) != triple) i += (src_[i] == '\\') ? 2 : 1;
        if (i >= src_.size()) return error(begin, line, col, "unterminated triple-quoted string");
        const std::string_view body = src_.substr(pos_ + 3, i - pos_ - 3);
        advanceOver(i + 3 - pos_);
        Token t = make(TokenKind::String, begin, line, col);
        t.value = unescape(body);
        return t;
    }
    size_t i = pos_ + 1;
    while (i < src_.size() && src_[i] != quote && src_[i] != '\n' && src_[i] != '\r') {
        if (src_[i] == '\\' && i + 1 < src_.size() && src_[i + 1] != '\n' && src_[i + 1] != '\r') ++i;
        ++i;
    }
    if (i >= src_.size() || src_[i] != quote) return error(begin, line, col, "unterminated string");
    const std::string_view body = src_.substr(pos_ + 1, i - pos_ - 1);
    pos_ = i + 1;
    Token t = make(TokenKind::String, begin, line, col);
    t.value = unescape(body);
    return t;
}

Token Lexer::scanAssetPath() {
    const size_t begin = pos_;
    const int col = column();
    if (at("@@@")) {
        // @@@...@@@ allows single and double @ inside and \@@@ for a literal @@@.
        std::string value;
        size_t i = pos_ + 3;
        for (;;) {
            if (i >= src_.size() || src_[i] == '\n' || src_[i] == '\r')
                return error(begin, line_, col, "unterminated asset path");
            if (src_.substr(i, 4) == "\\@@@") {
                value += "@@@";
                i += 4;
                continue;
            }
            // The closing delimiter is the last three of a run of @ (so "@@@a@@@@" is "a@").
            if (src_.substr(i, 3) == "@@@" && (i + 3 >= src_.size() || src_[i + 3] != '@')) break;
            value += src_[i++];
        }
        pos_ = i + 3;
        Token t = make(TokenKind::AssetPath, begin, line_, col);
        t.value = std::move(value);
        return t;
    }
    const size_t close = src_.find_first_of("@\n\r", pos_ + 1);
    if (close == std::string_view::npos || src_[close] != '@') return error(begin, line_, col, "unterminated asset path");
    std::string value(src_.substr(pos_ + 1, close - pos_ - 1));
    pos_ = close + 1;
    Token t = make(TokenKind::AssetPath, begin, line_, col);
    t.value = std::move(value);
    return t;
}

Token Lexer::scanPathRef() {
    const size_t begin = pos_;
    const int col = column();
    const size_t close = src_.find_first_of("<>\n\r", pos_ + 1);
    if (close == std::string_view::npos || src_[close] != '>') return error(begin, line_, col, "unterminated path '<...>'");
    pos_ = close + 1;
    Token t = make(TokenKind::PathRef, begin, line_, col);
    t.value = std::string(src_.substr(begin + 1, close - begin - 1));
    return t;
}

}  // namespace obscura::usda
