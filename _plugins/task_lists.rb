# frozen_string_literal: true

# Checklists a reader can tick. A GFM task list (`- [ ] item` or `- [x] item`) comes out of
# kramdown as a disabled checkbox before each item's text, ticked or not as the page was
# written: the reader could tick nothing. Here the checkboxes are taken out, so that
# without scripts the checklist is a plain list, and assets/js/site.js gives each item a
# checkbox of its own that the browser keeps per page (localStorage), with a button that
# clears them. Every item starts unticked, whatever the page's `[x]`.
#
# Each page's number of items goes into site.data["checklists"] (page URL -> count) before
# the pages are rendered, so that the sidebar (_includes/sidebar.html) can show each
# practice's progress over its pages.
module Sw2simSite
  module TaskLists
    CHECKBOX = %r{<input type="checkbox" class="task-list-item-checkbox"[^>]*/?>\s*}.freeze
    # `- [ ] ` or `* [x] ` at the start of a Markdown line (a list item of a task list).
    ITEM_SOURCE = /^\s*[-*+] \[[ xX]\] /.freeze

    module_function

    def plain(html)
      html.gsub(CHECKBOX, "")
    end

    def count(markdown)
      markdown.to_s.scan(ITEM_SOURCE).length
    end
  end
end

Jekyll::Hooks.register :site, :pre_render do |site|
  counts = {}
  (site.pages + site.documents).each do |page|
    next unless page.respond_to?(:extname) && %w[.md .markdown].include?(page.extname)

    items = Sw2simSite::TaskLists.count(page.content)
    counts[page.url] = items if items.positive?
  end
  site.data["checklists"] = counts
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::TaskLists.plain(page.content)
end
