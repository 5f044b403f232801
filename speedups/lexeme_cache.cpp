// LexemeCache: see lexeme_cache.h.
#include "speedups/lexeme_cache.h"

#include <atomic>
#include <cstring>

namespace povrayfc {

namespace {

// splitmix64's finaliser: every bit of the start reaches every bit of its bucket index.
std::uint64_t Finalize(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

}  // namespace

bool LexemeCache::Store(const LexemeStart &start, Lexeme::Kind kind, int tokenId, double value, int tokenColumn,
                        const StreamState &end, int endColumn, const char *text, std::size_t textLength,
                        int symbolSlot) {
    if (textLength > Lexeme::kMaxText) return false;
    auto found = index_.find(start);
    std::uint32_t index;
    if (found != index_.end()) {
        index = found->second;
    } else {
        index = static_cast<std::uint32_t>(lexemes_.size());
        lexemes_.emplace_back();
        index_.emplace(start, index);
    }
    Follows(index);
    Lexeme &lexeme = lexemes_[index];
    lexeme.start = start;
    lexeme.kind = kind;
    lexeme.tokenId = tokenId;
    lexeme.symbolSlot = symbolSlot;
    lexeme.value = value;
    lexeme.tokenColumn = tokenColumn;
    lexeme.end = end;
    lexeme.endColumn = endColumn;
    lexeme.textLength = static_cast<std::uint8_t>(textLength);
    std::memcpy(lexeme.text, text, textLength);
    lexeme.text[textLength] = '\0';
    return true;
}

std::size_t LexemeCache::StartHash::operator()(const LexemeStart &s) const {
    std::uint64_t h = s.stream * 0x9e3779b97f4a7c15ULL;
    h ^= static_cast<std::uint64_t>(s.state.offset) + 0x632be59bd9b4e019ULL + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(s.state.lineno) * 0xc2b2ae3d27d4eb4fULL;
    h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(s.state.pushedBack)) << 40;
    h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(s.column)) << 20;
    return static_cast<std::size_t>(Finalize(h));
}

std::uint64_t NewStreamSerial() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace povrayfc
