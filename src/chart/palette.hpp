#pragma once
// The colours of every chart: Okabe and Ito's palette, told apart by people with any common
// form of colour blindness (Okabe & Ito 2008, "Color Universal Design"). Series are also told
// apart by their order and their labels in the legend, never by colour alone.

#include <array>
#include <string_view>

namespace pagecache::chart {

inline constexpr std::string_view kOrange = "#E69F00";
inline constexpr std::string_view kSkyBlue = "#56B4E9";
inline constexpr std::string_view kBluishGreen = "#009E73";
inline constexpr std::string_view kYellow = "#F0E442";
inline constexpr std::string_view kBlue = "#0072B2";
inline constexpr std::string_view kVermillion = "#D55E00";
inline constexpr std::string_view kReddishPurple = "#CC79A7";
inline constexpr std::string_view kBlack = "#000000";

/// The palette in an order where neighbours contrast: series i takes colour i % 8.
inline constexpr std::array<std::string_view, 8> kPalette = {kBlue, kOrange, kBluishGreen, kVermillion,
                                                            kSkyBlue, kReddishPurple, kYellow, kBlack};

}  // namespace pagecache::chart
