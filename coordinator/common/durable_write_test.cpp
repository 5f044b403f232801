// durable_write_test.cpp - a file written durably is whole on disk, or not there with an error
// that names the call and the system's reason.
#include <sys/stat.h>
#include <unistd.h>


#include <gtest/gtest.h>

#include "durable_write.h"
#include "files.h"
#include "temp_dirs.h"

using namespace fc;

TEST(DurableWrite, WholeFileOrNoFile)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-durable-test-", dir, err)) << err;
    std::string path = dir + "/frame.tga";
    std::string bytes(100000, 'p');
    ASSERT_TRUE(write_file_durably(path, bytes.data(), bytes.size(), err)) << err;
    std::string back;
    ASSERT_TRUE(read_text(path, back, err));
    EXPECT_EQ(back, bytes);
    EXPECT_TRUE(sync_dir(dir, err)) << err;
    // Into a directory that is not there: no file, and the call and errno's text say why.
    EXPECT_FALSE(write_file_durably(dir + "/none/f", "x", 1, err));
    EXPECT_NE(err.find("open " + dir + "/none/f: No such file or directory"), std::string::npos)
        << err;
    remove_tree(dir);
    EXPECT_FALSE(file_exists(dir));
}
