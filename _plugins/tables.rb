# frozen_string_literal: true

# Wraps each table in a scrolling box, so a wide table scrolls on its own on a phone
# instead of widening the whole page. (`display: block` on the table itself would do the
# same but makes some browsers drop the table's semantics for screen readers.) The box
# takes focus so that it can be scrolled with the keyboard.
module Sw2simSite
  module Tables
    module_function

    def wrap(html)
      html.gsub(%r{<table\b.*?</table>}m) { |table| %(<div class="table-wrap" tabindex="0">#{table}</div>) }
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::Tables.wrap(page.content)
end
