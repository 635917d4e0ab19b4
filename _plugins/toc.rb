# frozen_string_literal: true

# `toc_entries`: a Liquid filter that lists the h2 and h3 headings of a page's rendered
# HTML, for the "On this page" box in _includes/toc.html. Building it at site-build time
# keeps the table of contents in the static HTML (no script needed to see it) and lets
# the tests check it.
#
# kramdown gives every heading an id (auto_ids), so a heading without one was written as
# raw HTML; it cannot be linked to and is left out.
module Sw2simSite
  module TocFilter
    HEADING = %r{<h([23])\b[^>]*?\bid="([^"]+)"[^>]*>(.*?)</h\1>}m.freeze
    TAG = %r{<[^>]+>}.freeze

    def toc_entries(html)
      html.to_s.scan(HEADING).map do |level, id, inner|
        # Headings may hold <code>, <em> or links; the box shows plain text. The text is
        # still HTML-escaped (entities stay as kramdown wrote them), so it is safe to print.
        text = inner.gsub(TAG, "").gsub(/\s+/, " ").strip
        { "level" => level.to_i, "id" => id, "text" => text }
      end
    end
  end
end

Liquid::Template.register_filter(Sw2simSite::TocFilter)
