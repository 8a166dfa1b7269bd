// Tokenizer for USD's text format. Newlines are tokens because the grammar uses them as
// statement separators; comments (#, //, /* */) and blanks are skipped.
#pragma once

#include <string>
#include <string_view>

namespace obscura::usda {

enum class TokenKind {
    EndOfFile,
    Newline,
    Magic,       // the "#usda 1.0" cookie on the first line
    Identifier,  // also keywords and namespaced names: "xformOp:rotateXYZ"
    Number,      // includes "-inf"; "inf" and "nan" come as identifiers
    String,      // value holds the text without quotes, escapes decoded
    AssetPath,   // value holds the text between the @ delimiters
    PathRef,     // value holds the text between < and >
    Punct,       // one of = , : ; . [ ] ( ) { }
    Error,       // value holds the message
};

struct Token {
    TokenKind kind = TokenKind::EndOfFile;
    std::string_view text;  // the raw source text
    std::string value;
    int line = 1;
    int column = 1;

    bool isPunct(char c) const { return kind == TokenKind::Punct && text.size() == 1 && text[0] == c; }
    bool isWord(std::string_view word) const { return kind == TokenKind::Identifier && text == word; }
};

// How a token reads in an error message: "'}'", "end of line", "string \"abc\"".
std::string describe(const Token& token);

class Lexer {
public:
    explicit Lexer(std::string_view source) : src_(source) {}

    const Token& peek();
    Token next();

private:
    Token scan();
    Token make(TokenKind kind, size_t begin, int line, int column);
    Token error(size_t begin, int line, int column, std::string message);
    Token scanNewline();
    Token scanIdentifier();
    Token scanNumber();
    Token scanString();
    Token scanAssetPath();
    Token scanPathRef();
    void advanceOver(size_t count);  // moves past text that may contain newlines, keeping line counts

    bool at(std::string_view s) const { return src_.substr(pos_, s.size()) == s; }
    char ch(size_t ahead = 0) const { return pos_ + ahead < src_.size() ? src_[pos_ + ahead] : '\0'; }
    int column() const { return static_cast<int>(pos_ - lineStart_) + 1; }

    std::string_view src_;
    size_t pos_ = 0;
    size_t lineStart_ = 0;
    int line_ = 1;
    Token peeked_;
    bool hasPeeked_ = false;
};

}  // namespace obscura::usda
