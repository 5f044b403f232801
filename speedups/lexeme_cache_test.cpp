#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "speedups/lexeme_cache.h"

using povrayfc::Lexeme;
using povrayfc::LexemeCache;
using povrayfc::LexemeStart;
using povrayfc::StreamState;

namespace {

LexemeStart StartAt(std::uint64_t stream, std::int64_t offset) {
    LexemeStart s;
    s.stream = stream;
    s.state.offset = offset;
    s.state.lineno = 7;
    s.state.pushedBack = ' ';
    s.column = 12;
    return s;
}

StreamState EndAt(std::int64_t offset) {
    StreamState e;
    e.offset = offset;
    e.lineno = 8;
    e.pushedBack = ';';
    return e;
}

}  // namespace

TEST(LexemeCache, FindsWhatWasStoredWithEverythingKept) {
    LexemeCache cache;
    ASSERT_TRUE(cache.Store(StartAt(3, 100), Lexeme::Kind::kNumber, 0, 0.25, 14, EndAt(105), 17, "0.25", 4));
    const Lexeme *l = cache.Find(StartAt(3, 100));
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->kind, Lexeme::Kind::kNumber);
    EXPECT_EQ(l->value, 0.25);
    EXPECT_EQ(l->tokenColumn, 14);
    EXPECT_EQ(l->end.offset, 105);
    EXPECT_EQ(l->end.lineno, 8);
    EXPECT_EQ(l->end.pushedBack, ';');
    EXPECT_EQ(l->endColumn, 17);
    EXPECT_EQ(std::string(l->text), "0.25");
    EXPECT_EQ(l->textLength, 4);
}

TEST(LexemeCache, KeepsASymbolsSlotAndReservedWord) {
    LexemeCache cache;
    ASSERT_TRUE(cache.Store(StartAt(3, 100), Lexeme::Kind::kSymbol, 17, 0, 14, EndAt(103), 15, "box", 3, 42));
    ASSERT_TRUE(cache.Store(StartAt(3, 104), Lexeme::Kind::kSymbol, Lexeme::kNotReserved, 0, 18, EndAt(107), 19,
                            "Pos", 3, 7));
    const Lexeme *l = cache.Find(StartAt(3, 100));
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->tokenId, 17);
    EXPECT_EQ(l->symbolSlot, 42);
    l = cache.Find(StartAt(3, 104));
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->tokenId, Lexeme::kNotReserved);
    EXPECT_EQ(l->symbolSlot, 7);
}

TEST(LexemeCache, AStartDiffersInAnyPartMisses) {
    LexemeCache cache;
    ASSERT_TRUE(cache.Store(StartAt(3, 100), Lexeme::Kind::kSymbol, 0, 0, 14, EndAt(103), 15, "K1t", 3));
    LexemeStart other = StartAt(4, 100);  // another stream (the same file opened again)
    EXPECT_EQ(cache.Find(other), nullptr);
    other = StartAt(3, 101);
    EXPECT_EQ(cache.Find(other), nullptr);
    other = StartAt(3, 100);
    other.state.lineno = 6;
    EXPECT_EQ(cache.Find(other), nullptr);
    other = StartAt(3, 100);
    other.state.pushedBack = -1;  // nothing pushed back: the next character comes from the file
    EXPECT_EQ(cache.Find(other), nullptr);
    other = StartAt(3, 100);
    other.column = 0;  // the column counter would come out differently
    EXPECT_EQ(cache.Find(other), nullptr);
    EXPECT_NE(cache.Find(StartAt(3, 100)), nullptr);
}

TEST(LexemeCache, StoringAgainReplacesAndClearForgets) {
    LexemeCache cache;
    ASSERT_TRUE(cache.Store(StartAt(1, 0), Lexeme::Kind::kPunctuation, 5, 0, 0, EndAt(1), 1, "{", 1));
    ASSERT_TRUE(cache.Store(StartAt(1, 0), Lexeme::Kind::kDirective, 0, 0, 0, EndAt(1), 1, "#", 1));
    EXPECT_EQ(cache.Size(), 1u);
    EXPECT_EQ(cache.Find(StartAt(1, 0))->kind, Lexeme::Kind::kDirective);
    EXPECT_EQ(std::string(cache.Find(StartAt(1, 0))->text), "#");
    cache.Clear();
    EXPECT_EQ(cache.Find(StartAt(1, 0)), nullptr);
    EXPECT_EQ(cache.Size(), 0u);
}

TEST(LexemeCache, KeepsNoTokenLongerThanItsBuffer) {
    LexemeCache cache;
    const std::string longest(Lexeme::kMaxText, 'x');
    const std::string tooLong(Lexeme::kMaxText + 1, 'x');
    EXPECT_TRUE(cache.Store(StartAt(1, 0), Lexeme::Kind::kSymbol, 0, 0, 0, EndAt(47), 47, longest.c_str(),
                            longest.size()));
    EXPECT_EQ(std::string(cache.Find(StartAt(1, 0))->text), longest);
    EXPECT_FALSE(cache.Store(StartAt(1, 100), Lexeme::Kind::kSymbol, 0, 0, 0, EndAt(148), 48, tooLong.c_str(),
                             tooLong.size()));
    EXPECT_EQ(cache.Find(StartAt(1, 100)), nullptr);
}

TEST(LexemeCache, ManyStartsInOneStreamAllFound) {
    LexemeCache cache;
    for (int i = 0; i < 5000; ++i) {
        const std::string text = std::to_string(i);
        ASSERT_TRUE(cache.Store(StartAt(9, i * 3), Lexeme::Kind::kNumber, 0, i, 0, EndAt(i * 3 + 2), 2,
                                text.c_str(), text.size()));
    }
    for (int i = 0; i < 5000; ++i) {
        const Lexeme *l = cache.Find(StartAt(9, i * 3));
        ASSERT_NE(l, nullptr);
        EXPECT_EQ(l->value, i);
        EXPECT_EQ(cache.Find(StartAt(9, i * 3 + 1)), nullptr);
    }
}

TEST(StreamSerial, NeverRepeats) {
    std::set<std::uint64_t> seen;
    for (int i = 0; i < 1000; ++i) EXPECT_TRUE(seen.insert(povrayfc::NewStreamSerial()).second);
    EXPECT_EQ(seen.count(0), 0u);  // 0 is no stream
}

TEST(LexemeCache, FollowsTheOrderOfTheLastPassAndFindsAnotherOrderToo) {
    // A loop body whose #if takes another branch on some passes: a, b, d on one pass,
    // a, c, d on another. Whatever the order, each start finds its own lexeme.
    LexemeCache cache;
    const char *names[] = {"a", "b", "c", "d"};
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(cache.Store(StartAt(2, i * 10), Lexeme::Kind::kSymbol, 0, 0, 0, EndAt(i * 10 + 1), 1,
                                names[i], 1));
    const int passes[][3] = {{0, 1, 3}, {0, 2, 3}, {0, 2, 3}, {0, 1, 3}, {3, 0, 1}};
    for (const auto &pass : passes) {
        for (int i : pass) {
            const Lexeme *l = cache.Find(StartAt(2, i * 10));
            ASSERT_NE(l, nullptr);
            EXPECT_EQ(std::string(l->text), names[i]);
            EXPECT_EQ(l->start, StartAt(2, i * 10));
        }
        EXPECT_EQ(cache.Find(StartAt(2, 5)), nullptr);  // a start never kept, between the others
    }
}
