// The frame record as the renderer writes it and fc-slave reads it back.
#include "frame-channel/frame_record.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fc {
namespace {

FrameRecord TwoTiles()
{
    FrameRecord rec;
    rec.frame = 7;
    rec.rays = 123456;
    rec.parse_seconds = 0.25;
    rec.trace_seconds = 1.5;
    rec.encoding = "rgb8";
    rec.rects = {Rect{0, 0, 2, 1}, Rect{4, 3, 5, 5}};
    rec.data = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};       // 2 + 2 pixels
    rec.file_gamma = 2.2f;
    return rec;
}

std::string Stream(const FrameRecord &rec)
{
    std::string s = record_header(rec);
    s.append(rec.data.begin(), rec.data.end());
    s.append(rec.file.begin(), rec.file.end());
    s += rec.reads;
    return s;
}

TEST(FrameRecord, HeaderIsTheDocumentedLine)
{
    EXPECT_EQ(record_header(TwoTiles()),
              "FCFRAME 1 frame=7 rays=123456 parse=0.250000 trace=1.500000 encoding=rgb8 "
              "rects=2 0,0,2,1 4,3,5,5 file_gamma=2.20000005 bytes=12\n");
    FrameRecord whole = TwoTiles();
    whole.rects = {Rect{0, 0, 2, 2}};
    whole.file = {'T', 'G', 'A'};
    whole.rays = -1;
    EXPECT_EQ(record_header(whole),
              "FCFRAME 1 frame=7 rays=-1 parse=0.250000 trace=1.500000 encoding=rgb8 "
              "rects=1 0,0,2,2 file=3 file_gamma=2.20000005 bytes=12\n");
    // The reads section's size comes before bytes=B; without reads the field is left out.
    whole.reads = "F\tscene.pov\nA\tlate.inc\n";
    EXPECT_EQ(record_header(whole),
              "FCFRAME 1 frame=7 rays=-1 parse=0.250000 trace=1.500000 encoding=rgb8 "
              "rects=1 0,0,2,2 file=3 file_gamma=2.20000005 reads=23 bytes=12\n");
}

TEST(FrameRecord, WrittenRecordsReadBackWhateverTheBytesArriveIn)
{
    FrameRecord a = TwoTiles(), b = TwoTiles();
    b.frame = 8;
    b.rects = {Rect{0, 0, 2, 2}};
    b.file = {'P', 'N', 'G', 0};
    b.reads = "F\t/usr/share/povray-3.7/include/colors.inc\nA\tcolors.inc\n";
    std::string stream = Stream(a) + Stream(b);
    for (size_t chunk : {size_t(1), size_t(5), stream.size()}) {
        FrameRecordReader reader;
        std::vector<FrameRecord> got;
        std::string err;
        for (size_t at = 0; at < stream.size(); at += chunk) {
            reader.feed(stream.data() + at, std::min(chunk, stream.size() - at));
            FrameRecord rec;
            int r;
            while ((r = reader.next(rec, err)) == 1)
                got.push_back(rec);
            ASSERT_EQ(r, 0) << err;
        }
        ASSERT_EQ(got.size(), 2u) << "chunk " << chunk;
        EXPECT_EQ(reader.pending(), 0u);
        for (int k = 0; k < 2; k++) {
            const FrameRecord &want = k == 0 ? a : b;
            EXPECT_EQ(got[k].frame, want.frame);
            EXPECT_EQ(got[k].rays, want.rays);
            EXPECT_EQ(got[k].parse_seconds, want.parse_seconds);
            EXPECT_EQ(got[k].trace_seconds, want.trace_seconds);
            EXPECT_EQ(got[k].encoding, want.encoding);
            EXPECT_EQ(got[k].rects, want.rects);
            EXPECT_EQ(got[k].data, want.data);
            EXPECT_EQ(got[k].file, want.file);
            EXPECT_EQ(got[k].reads, want.reads);
            EXPECT_FLOAT_EQ(float(got[k].file_gamma), 2.2f);
        }
    }
}

TEST(FrameRecord, MalformedHeadersAreRefusedWithTheReason)
{
    struct Case {
        const char *line, *reason;
    } cases[] = {
        {"P6 160 120", "not a frame record"},
        {"FCFRAME 2 frame=1", "not a frame record"},
        {"FCFRAME 1 frame=1 rects=1 0,0,1,1 encoding=rgb8 bytes", "without '='"},
        {"FCFRAME 1 frame=x rects=1 0,0,1,1 encoding=rgb8 bytes=3", "frame is not a number"},
        {"FCFRAME 1 frame=1 rects=1 0,0,0,1 encoding=rgb8 bytes=3", "rectangle 1 is malformed"},
        {"FCFRAME 1 frame=1 rects=1 0,0,1,1 encoding=yuv bytes=3", "known encoding"},
        {"FCFRAME 1 frame=1 rects=1 0,0,1,1 encoding=rgb8", "known encoding"},
        {"FCFRAME 1 frame=1 rects=1 0,0,2,1 encoding=rgb8 bytes=3", "has 3 bytes for 2 pixels"},
        {"FCFRAME 1 frame=1 rects=1 0,0,1,1 encoding=rgbf bytes=12", "has 12 bytes for 1 pixels"},
        {"FCFRAME 1 frame=1 rects=1 0,0,1,1 encoding=rgb8 reads=-1 bytes=3", "reads size"},
        {"FCFRAME 1 frame=1 rects=1 0,0,1,1 encoding=rgb8 reads=x bytes=3", "reads is not"},
    };
    for (const Case &c : cases) {
        FrameRecord rec;
        RecordSizes sizes;
        std::string err;
        EXPECT_FALSE(parse_record_header(c.line, rec, sizes, err)) << c.line;
        EXPECT_NE(err.find(c.reason), std::string::npos) << c.line << ": " << err;
    }
}

TEST(FrameRecord, UnknownFieldsAreSkipped)
{
    FrameRecord rec;
    RecordSizes sizes;
    std::string err;
    ASSERT_TRUE(parse_record_header(
        "FCFRAME 1 frame=3 later=9 rects=1 0,0,1,2 encoding=rgb16 bytes=12", rec, sizes, err))
        << err;
    EXPECT_EQ(rec.frame, 3);
    EXPECT_EQ(sizes.pixels, 12u);
    EXPECT_EQ(sizes.file, 0u);
    EXPECT_EQ(sizes.reads, 0u);
}

// The reads section follows the pixels and the file, and a record is complete only with it.
TEST(FrameRecord, ReadsFollowThePixelsAndTheFile)
{
    FrameRecord rec = TwoTiles();
    rec.rects = {Rect{0, 0, 2, 2}};
    rec.file = {'T', 'G', 'A'};
    rec.reads = "F\tscene.pov\nA\tdata.txt\nA\t/usr/share/povray-3.7/include/data.txt\n";
    std::string stream = Stream(rec), err;
    FrameRecordReader reader;
    reader.feed(stream.data(), stream.size() - 1);
    FrameRecord got;
    ASSERT_EQ(reader.next(got, err), 0) << err;         // its last byte is missing
    reader.feed(stream.data() + stream.size() - 1, 1);
    ASSERT_EQ(reader.next(got, err), 1) << err;
    EXPECT_EQ(got.data, rec.data);
    EXPECT_EQ(got.file, rec.file);
    EXPECT_EQ(got.reads, rec.reads);
    EXPECT_EQ(reader.pending(), 0u);
}

TEST(FrameRecord, DiffusionFollowsThePixels)
{
    FrameRecord rec;
    rec.frame = 2;
    rec.encoding = "rgbf";
    rec.rects = {Rect{0, 0, 2, 1}};
    const float values[6] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    const uint8_t *p = reinterpret_cast<const uint8_t *>(values);
    rec.data.assign(p, p + sizeof values);
    Diffusion d;
    d.method = 3;
    d.working_gamma_type = 1;
    d.working_gamma = 1.0f;
    d.file_gamma_type = 2;
    d.file_gamma = 2.2f;
    append_diffusion(d, rec.data);

    FrameRecordReader reader;
    std::string stream = Stream(rec), err;
    reader.feed(stream.data(), stream.size());
    FrameRecord got;
    ASSERT_EQ(reader.next(got, err), 1) << err;
    Diffusion back;
    ASSERT_TRUE(parse_diffusion(got.data, 2, back, err)) << err;
    EXPECT_EQ(back.method, 3);
    EXPECT_EQ(back.working_gamma_type, 1);
    EXPECT_EQ(back.working_gamma, 1.0f);
    EXPECT_EQ(back.file_gamma_type, 2);
    EXPECT_EQ(back.file_gamma, 2.2f);

    EXPECT_FALSE(parse_diffusion(got.data, 1, back, err));
    d.method = 4;       // Bayer 2x2: not carried over tiles
    rec.data.resize(sizeof values);
    append_diffusion(d, rec.data);
    EXPECT_FALSE(parse_diffusion(rec.data, 2, back, err));
    EXPECT_NE(err.find("method 4"), std::string::npos) << err;
}

} // namespace
} // namespace fc
