// LexemeCache: the tokens a parse read at a place in a scene file, for the next time it
// reads there.
//
// POV-Ray's tokenizer reads a scene character by character, and a #while loop or a macro
// body is read again, character by character, on every pass (the stream seeks back to the
// loop's start). Newton integrates its motion in such a loop, up to 400 passes a frame:
// reading characters, skipping blanks and converting numbers was a third of its parse.
// The patched tokenizer keeps, for each token it lexes inside a loop or macro, where the
// token began (which stream, where in it, with what state) and what it found: the token's
// characters, its kind and number value, and the state of the stream after it. On a later
// pass the same start gives the same characters, so it gives the same token: the tokenizer
// sets the stream to the stored end and goes on from the token as if it had read it.
// It keeps tokens only from a stream that went back once (a loop's second pass, a macro of
// the same file): a file opened anew per call of a macro in another file is never read
// twice from the same stream, and keeping its tokens only cost time.
//
// Only the reading is replayed. What a token means (an identifier's current value, a
// directive's effect) is worked out again every time, by POV-Ray's own code. What follows
// from a symbol's characters alone is kept too: where its name hashes to in the parser's
// tables, and whether it is a reserved word (whose table never changes).
//
// Exactness: a start matches only the same stream object (a serial number that no other
// stream in the process gets, so a file opened anew, perhaps rewritten meanwhile, never
// matches), the same byte offset and pending pushed-back character, the same line number
// and the same column counter (POV-Ray's error messages report it). Everything the
// tokenizer's reading changes is in the stored end state.
#ifndef SPEEDUPS_LEXEME_CACHE_H
#define SPEEDUPS_LEXEME_CACHE_H

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace povrayfc {

// Where a text stream stands: everything its next characters and line numbers depend on.
struct StreamState {
    std::int64_t offset = 0;    // of the next byte in the file (a pushed-back character aside)
    std::int64_t lineno = 0;
    int pushedBack = -1;        // the character ungetchar() left, or -1 (EOF) for none
};

// Where the tokenizer began reading a token.
struct LexemeStart {
    std::uint64_t stream = 0;   // the stream's serial number
    StreamState state;
    int column = 0;             // the tokenizer's column counter (Echo_Indx)

    bool operator==(const LexemeStart &o) const {
        return stream == o.stream && state.offset == o.state.offset && state.lineno == o.state.lineno &&
               state.pushedBack == o.state.pushedBack && column == o.column;
    }
};

struct Lexeme {
    static constexpr std::uint32_t kNone = 0xffffffffu;
    static constexpr int kNotReserved = -1;     // kSymbol: an identifier, not a reserved word

    enum class Kind : std::uint8_t {
        kPunctuation,   // a token the tokenizer writes as it reads it ({, <=, ...)
        kNumber,        // a float literal, with its value
        kSymbol,        // a keyword or identifier: its name, to be looked up again
        kDirective,     // '#': the directive is parsed again
    };
    static constexpr std::size_t kMaxText = 47;   // longer tokens are not kept

    LexemeStart start;          // where it was read from
    std::uint32_t next = kNone; // the lexeme read after it last time (a hint, see Find)
    Kind kind = Kind::kPunctuation;
    int tokenId = 0;            // kPunctuation: the token written; kSymbol: the reserved word's
                                // token, or kNotReserved
    int symbolSlot = -1;        // kSymbol: the slot its name hashes to in the parser's tables
                                // (a kSymbol is always stored with it and with tokenId)
    double value = 0.0;         // kNumber
    int tokenColumn = 0;        // the column the token was reported at
    StreamState end;            // the stream after the token (its look-ahead pushed back)
    int endColumn = 0;          // the column counter after the token
    std::uint8_t textLength = 0;
    char text[kMaxText + 1] = {};   // the tokenizer's string buffer after the token
};

class LexemeCache {
public:
    // Forget every lexeme (a new parse).
    void Clear() {
        lexemes_.clear();
        index_.clear();
        last_ = Lexeme::kNone;
    }

    // The lexeme read from `start` before, or null. A pass through a loop body mostly
    // meets the lexemes in the order it met them last time: the one found or kept last
    // names the one that followed it, which is taken when its start is `start`, without
    // hashing (the hash lookup was a fifth of Newton's parse); otherwise the index says.
    // The pointer is good until the next Store: copy the lexeme to keep it longer.
    const Lexeme *Find(const LexemeStart &start) {
        if (last_ != Lexeme::kNone) {
            const std::uint32_t next = lexemes_[last_].next;
            if (next != Lexeme::kNone && lexemes_[next].start == start) {
                last_ = next;
                return &lexemes_[next];
            }
        }
        auto it = index_.find(start);
        if (it == index_.end()) return nullptr;
        Follows(it->second);
        return &lexemes_[it->second];
    }

    // Keeps what was read from `start` (replacing what was); false (nothing kept) when
    // the text is longer than Lexeme::kMaxText.
    bool Store(const LexemeStart &start, Lexeme::Kind kind, int tokenId, double value, int tokenColumn,
               const StreamState &end, int endColumn, const char *text, std::size_t textLength,
               int symbolSlot = -1);

    std::size_t Size() const { return lexemes_.size(); }

private:
    struct StartHash {
        std::size_t operator()(const LexemeStart &s) const;
    };
    // `index` was found or kept just now: it follows the last one.
    void Follows(std::uint32_t index) {
        if (last_ != Lexeme::kNone) lexemes_[last_].next = index;
        last_ = index;
    }
    std::vector<Lexeme> lexemes_;
    std::unordered_map<LexemeStart, std::uint32_t, StartHash> index_;
    std::uint32_t last_ = Lexeme::kNone;
};

// A serial number for a new stream: no two calls in a process return the same one.
std::uint64_t NewStreamSerial();

}  // namespace povrayfc

#endif
