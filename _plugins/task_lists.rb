# frozen_string_literal: true

# GFM task lists (`- [x] done`, `- [ ] to do`) come out of kramdown as a disabled
# checkbox followed by the item's text, with nothing tying the two together: a screen
# reader announces "checkbox, checked" and no name. Wrapping checkbox and text in a
# <label> makes the text the checkbox's name. Only the item's first line of inline
# content is wrapped; a nested list or a second paragraph stays outside the label.
module Sw2simSite
  module TaskLists
    ITEM = %r{(<input type="checkbox" class="task-list-item-checkbox"[^>]*>)(.*?)(?=</li>|</p>|<ul|<ol|<div)}m.freeze

    module_function

    def label(html)
      html.gsub(ITEM) { %(<label class="task-list-label">#{Regexp.last_match(1)}#{Regexp.last_match(2).rstrip}</label>) }
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::TaskLists.label(page.content)
end
