// ListOp: Sdf's list editing applied over weaker opinions.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "harness/usda/list_op.h"

namespace obscura::usda {
namespace {

using Names = std::vector<std::string>;

ListOp<std::string> op(ListOpKind kind, Names items) {
    ListOp<std::string> result;
    result.set(kind, std::move(items));
    return result;
}

TEST(ListOp, ExplicitReplacesWeaker) {
    EXPECT_EQ(op(ListOpKind::Explicit, {"a"}).applyTo({"x", "y"}), Names{"a"});
    EXPECT_EQ(op(ListOpKind::Explicit, {}).applyTo({"x"}), Names{});
    EXPECT_TRUE(op(ListOpKind::Explicit, {}).hasOpinion());
    EXPECT_FALSE(ListOp<std::string>{}.hasOpinion());
}

TEST(ListOp, PrependAppendAddDelete) {
    EXPECT_EQ(op(ListOpKind::Prepend, {"a", "y"}).applyTo({"x", "y"}), (Names{"a", "y", "x"}));
    EXPECT_EQ(op(ListOpKind::Append, {"x", "b"}).applyTo({"x", "y"}), (Names{"y", "x", "b"}));
    EXPECT_EQ(op(ListOpKind::Add, {"x", "b"}).applyTo({"x", "y"}), (Names{"x", "y", "b"}));
    EXPECT_EQ(op(ListOpKind::Delete, {"x", "z"}).applyTo({"x", "y"}), Names{"y"});
    EXPECT_EQ(op(ListOpKind::Reorder, {"y", "q", "x"}).applyTo({"x", "z", "y"}), (Names{"y", "x", "z"}));
}

TEST(ListOp, SettingAnEditLeavesExplicitMode) {
    ListOp<std::string> edits = op(ListOpKind::Explicit, {"a"});
    edits.set(ListOpKind::Prepend, {"b"});
    edits.set(ListOpKind::Delete, {"x"});
    EXPECT_EQ(edits.applyTo({"x", "y"}), (Names{"b", "y"}));
}

TEST(ListOp, ComposeStrongestFirst) {
    const ListOp<std::string> weak = op(ListOpKind::Explicit, {"a", "b"});
    const ListOp<std::string> strong = op(ListOpKind::Delete, {"a"});
    EXPECT_EQ(composeListOps<std::string>({&strong, &weak}), Names{"b"});
    EXPECT_EQ(composeListOps<std::string>({&weak, &strong}), (Names{"a", "b"}));
}

}  // namespace
}  // namespace obscura::usda
